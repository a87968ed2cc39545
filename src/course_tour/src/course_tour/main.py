"""`rosrun course_tour tour [LAB ...]`, what ./demo.sh runs: the course's labs, headless, one after
the other, and a summary of what each did."""
import argparse
import datetime
import os
import sys
import time
import traceback

from course_tour.labs import LABS
from course_tour.session import Session
from course_common.processes import exit_on_terminate, restore_ctrl_c


def parse_args(argv):
    names = [lab.name for lab in LABS]
    parser = argparse.ArgumentParser(
        prog='./demo.sh', description='Run the labs of the course headless and summarise them.')
    parser.add_argument('labs', nargs='*', metavar='LAB',
                        help='labs to run (default: all): %s' % ', '.join(names))
    parser.add_argument('--output', metavar='DIR',
                        help='folder for the pictures and logs (default: output/tour-<time>)')
    args = parser.parse_args(argv)
    unknown = [name for name in args.labs if name not in names]
    if unknown:
        parser.error('unknown lab %s; the labs are: %s' % (', '.join(unknown), ', '.join(names)))
    return args


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    restore_ctrl_c()  # each lab is stopped with SIGINT, also when ./demo.sh runs in the background
    exit_on_terminate()   # killed or its terminal closed: the session still stops what the labs started
    chosen = [lab for lab in LABS if not args.labs or lab.name in args.labs]
    output = args.output or os.path.join(
        os.getcwd(), 'output', 'tour-' + datetime.datetime.now().strftime('%Y%m%d-%H%M%S'))
    output = os.path.abspath(output)
    os.makedirs(output, exist_ok=True)

    results = []
    with Session(output) as session:
        for number, lab in enumerate(chosen, 1):
            print('[%d/%d] %s: %s ...' % (number, len(chosen), lab.name, lab.title), flush=True)
            start = time.monotonic()
            try:
                report = lab.run(session)
            except Exception as error:  # one broken lab must not hide the others' results
                with open(os.path.join(output, 'logs', lab.name + '.error'), 'w') as details:
                    traceback.print_exc(file=details)
                results.append((lab, None, str(error)))
                print('      FAILED after %.0f s: %s' % (time.monotonic() - start, error), flush=True)
                continue
            finally:
                session.stop_all()  # nothing of one lab may run into the next
            results.append((lab, report, None))
            print('      done in %.0f s' % (time.monotonic() - start), flush=True)

    print('\nSummary')
    for lab, report, error in results:
        if error:
            print('  %-8s FAILED: %s' % (lab.name, error))
            continue
        for index, line in enumerate(report.lines):
            print('  %-8s %s' % (lab.name if index == 0 else '', line))
        for picture in report.pictures:
            print('  %-8s picture: %s' % ('', os.path.basename(picture)))
    print('\nPictures and logs are in %s' % output)
    return 1 if any(error for _, _, error in results) else 0
