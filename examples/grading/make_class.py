#!/usr/bin/env python3
"""Writes an example class as a teacher gets it: one folder per student of examples/grading/LAB/
expected.yaml, the ones made by one change to the model (STUDENT.patch, a unified diff for GNU
patch) included.
Usage: examples/grading/make_class.py LAB OUT   (then: ./grade.sh LAB OUT/* --out grades)"""
import os
import shutil
import subprocess
import sys

import yaml

HERE = os.path.dirname(os.path.abspath(__file__))


def make_class(lab, out):
    """The folders of the class's students in `out`, sorted by name; returns their paths."""
    folder = os.path.join(HERE, lab)
    with open(os.path.join(folder, 'expected.yaml')) as stream:
        students = sorted(yaml.safe_load(stream))
    paths = []
    for student in students:
        target = os.path.join(out, student)
        patch = os.path.join(folder, student + '.patch')
        if os.path.exists(patch):   # the model with one change
            model = os.path.realpath(os.path.join(folder, 'model'))
            shutil.copytree(model, os.path.join(target, os.path.basename(model)), symlinks=True)
            # patch, not git: the course image has no git.
            subprocess.run(['patch', '-p1', '--batch', '--quiet', '--no-backup-if-mismatch', '-i', patch], cwd=target,
                           check=True)
        else:
            shutil.copytree(os.path.realpath(os.path.join(folder, student)), target, symlinks=True)
        paths.append(target)
    return paths


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__.splitlines()[-1].strip())
    print('\n'.join(make_class(sys.argv[1], sys.argv[2])))
