"""The student of each test file: a home and a workspace of their own, made by tools/new-workspace.sh."""
import shutil

import pytest

from test_student_workspace import new_student


@pytest.fixture(scope='module')
def student():
    someone, printed = new_student()
    assert 'source %s/devel/setup.bash' % someone.workspace in printed
    yield someone
    someone.stop_all()
    shutil.rmtree(someone.home)
