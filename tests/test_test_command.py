"""./test.sh runs every test on its first run on a fresh machine, and fails when a step finds none.

Each case runs the real test.sh, count_results.py and run_test_jobs.py in a small workspace of its
own, with a tools/setup.sh and tools/env.sh that install and build nothing, and with a PATH that has
no catkin on it (as on a fresh machine before tools/setup.sh has installed it).
"""
import importlib.util
import os
import shutil
import signal
import subprocess

import pytest

from course_common.process_table import command_line
from course_testing.processes import ignored_signals

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# What test.sh may run before tools/setup.sh has installed anything: a fresh Debian's base tools.
BASE_TOOLS = ['bash', 'cat', 'dirname', 'env', 'find', 'head', 'id', 'rm', 'mkdir', 'sed', 'sort',
              'tail', 'tr', 'wc']

SETUP = """#!/bin/bash
# Installs nothing and builds nothing; says that it ran (test.sh must call it before any catkin tool).
echo "setup $*" >> "$(dirname "$0")/../setup_calls.txt"
"""
ENV = """# After setup: Debian's tools, and the fake rostest in front of them.
export PATH="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/fake_bin:/usr/bin:/bin"
"""
# Writes nothing and exits 0: a rostest that registered a test but left no result file.
SILENT_ROSTEST = '#!/bin/bash\nexit 0\n'
# Writes a passing wrapper and the test node's results, as rostest does.
GOOD_ROSTEST = """#!/bin/bash
for arg; do case "$arg" in --package=*) pkg=${arg#--package=};; esac; done
while [ $# -gt 0 ]; do
    case "$1" in --results-filename) name=${2%.xml}; shift;; --results-base-dir) base=$2; shift;; esac
    shift
done
mkdir -p "$base/$pkg"
echo '<testsuite><testcase classname="r" name="testnode"/></testsuite>' > "$base/$pkg/rostest-$name.xml"
echo '<testsuite><testcase classname="n" name="case"/></testsuite>' > "$base/$pkg/rosunit-node.xml"
"""
PACKAGE_XML = '<?xml version="1.0"?>\n<package format="2">\n  <name>%s</name>\n</package>\n'
PASSING_TESTS = 'def test_one():\n    assert 1 + 1 == 2\n\n\ndef test_two():\n    assert "ab".upper() == "AB"\n'


def write(path, text, mode=0o644):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as out:
        out.write(text)
    os.chmod(path, mode)


@pytest.fixture
def workspace(tmp_path):
    """A workspace with test.sh and its tools, two packages with two unit tests each, tests/ with one."""
    ws = tmp_path / 'ws'
    for name in ('test.sh', 'tools/count_results.py', 'tools/run_test_jobs.py'):
        os.makedirs(str((ws / name).parent), exist_ok=True)
        shutil.copy2(os.path.join(ROOT, name), str(ws / name))
    write(str(ws / 'tools/setup.sh'), SETUP, 0o755)
    write(str(ws / 'tools/env.sh'), ENV)
    write(str(ws / 'tools/fake_bin/rostest'), GOOD_ROSTEST, 0o755)
    add_package(ws, 'src/alpha', 'alpha', {'test_alpha.py': PASSING_TESTS})
    add_package(ws, 'src/group/beta', 'beta', {'test_beta.py': PASSING_TESTS})
    write(str(ws / 'tests/test_workspace.py'), 'def test_workspace():\n    assert True\n')
    bin_dir = tmp_path / 'bin'  # every base tool, and no catkin
    bin_dir.mkdir()
    for tool in BASE_TOOLS:
        os.symlink(shutil.which(tool, path='/usr/bin:/bin'), str(bin_dir / tool))
    return ws


def add_package(ws, folder, name, unit_files, rostests=()):
    write(str(ws / folder / 'package.xml'), PACKAGE_XML % name)
    write(str(ws / folder / 'CMakeLists.txt'), 'project(%s)\n' % name + ''.join(
        'add_rostest(%s)\n' % test for test in rostests))
    for file_name, text in unit_files.items():
        write(str(ws / folder / 'test/unit' / file_name), text)


def run_test_command(ws, *packages):
    # PYTHONPATH: the course's packages, which tools/env.sh gives test.sh after the build.
    env = {'PATH': str(ws.parent / 'bin'), 'HOME': str(ws.parent), 'PYTHONPATH': os.environ['PYTHONPATH']}
    result = subprocess.run([str(ws / 'test.sh')] + list(packages), env=env, stdin=subprocess.DEVNULL,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True,
                            timeout=120)
    return result.returncode, result.stdout


def last_line(output):
    return output.rstrip().splitlines()[-1]


def test_catkin_is_not_needed_to_find_the_packages_and_every_unit_test_runs(workspace):
    assert shutil.which('catkin_topological_order', path=str(workspace.parent / 'bin')) is None
    code, output = run_test_command(workspace)
    assert (code, last_line(output)) == (0, '5 passed, 0 failed'), output
    assert 'test: pytest src/alpha/test/unit' in output and 'test: pytest src/group/beta/test/unit' in output
    assert 'command not found' not in output
    assert (workspace / 'setup_calls.txt').read_text().startswith('setup \n')


def test_a_package_whose_unit_folder_has_no_tests_fails_the_run(workspace):
    add_package(workspace, 'src/gamma', 'gamma', {'helpers.py': 'HELP = 1\n'})
    code, output = run_test_command(workspace)
    assert (code, last_line(output)) == (1, '5 passed, 2 failed'), output
    assert 'FAILED: pytest src/gamma/test/unit collected no tests (exit 5)' in output
    assert 'FAILED: pytest/gamma.xml: no test results' in output


def test_a_unit_test_that_cannot_be_imported_fails_the_run(workspace):
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': 'import no_such_module\n'})
    code, output = run_test_command(workspace, 'gamma')
    assert code == 1 and 'FAILED' in output, output
    assert last_line(output) != '0 passed, 0 failed'


def test_a_rostest_that_leaves_no_result_file_fails_the_run(workspace):
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': PASSING_TESTS},
                rostests=['test/quiet.test', 'test/good.test'])
    write(str(workspace / 'tools/fake_bin/rostest'),
          '#!/bin/bash\ncase "$*" in *quiet.test*) exit 0;; esac\n' + GOOD_ROSTEST, 0o755)
    code, output = run_test_command(workspace, 'gamma')
    assert (code, last_line(output)) == (1, '3 passed, 1 failed'), output
    assert 'FAILED: gamma/rostest-test_quiet.xml: no test results' in output
    assert 'test: rostest gamma/test/quiet.test' in output and 'test: rostest gamma/test/good.test' in output


def test_a_rostest_that_is_killed_fails_the_run_even_with_its_results_written(workspace):
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': PASSING_TESTS}, rostests=['test/x.test'])
    write(str(workspace / 'tools/fake_bin/rostest'), GOOD_ROSTEST + 'kill -9 $$\n', 0o755)
    code, output = run_test_command(workspace, 'gamma')
    assert (code, last_line(output)) == (1, '3 passed, 1 failed'), output
    assert 'FAILED: rostest gamma/test/x.test (exit -9: its results cannot be trusted' in output


def test_a_rostest_that_leaves_a_process_running_fails_the_run_and_the_process_is_stopped(workspace, tmp_path):
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': PASSING_TESTS}, rostests=['test/x.test'])
    pid_file = tmp_path / 'left.pid'
    # As a roslaunch node: a session of its own, reparented to init when the test ends.
    write(str(workspace / 'tools/fake_bin/rostest'),
          GOOD_ROSTEST + 'setsid -f bash -c \'echo $$ > %s; exec sleep 600\'\n' % pid_file, 0o755)
    code, output = run_test_command(workspace, 'gamma')
    pid = int(pid_file.read_text())
    assert (code, last_line(output)) == (1, '3 passed, 1 failed'), output
    assert 'left running: %d sleep 600' % pid in output
    assert 'FAILED: rostest gamma/test/x.test left 1 process running (killed now): %d sleep 600' % pid in output
    assert not command_line(pid).endswith(' sleep 600')   # killed


def test_a_process_left_running_is_one_failure_whatever_lines_its_command_has(workspace, tmp_path):
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': PASSING_TESTS}, rostests=['test/x.test'])
    pid_file = tmp_path / 'left.pid'
    # A `python3 -c` program of two lines, as a test's stand-in node (each line once counted as a failure).
    write(str(workspace / 'tools/fake_bin/rostest'),
          GOOD_ROSTEST + 'setsid -f bash -c \'echo $$ > %s; exec /usr/bin/python3 -c "import time\ntime.sleep(600)"\'\n'
          % pid_file, 0o755)
    code, output = run_test_command(workspace, 'gamma')
    pid = int(pid_file.read_text())
    assert (code, last_line(output)) == (1, '3 passed, 1 failed'), output
    assert ('FAILED: rostest gamma/test/x.test left 1 process running (killed now): %d /usr/bin/python3 -c '
            'import time\\ntime.sleep(600)' % pid) in output


def test_each_test_file_of_tests_student_is_a_slow_step_of_its_own(workspace):
    for name in ('test_one.py', 'test_two.py'):
        write(str(workspace / 'tests/student' / name), PASSING_TESTS)
    write(str(workspace / 'tests/student/helpers.py'), 'HELP = 1\n')
    code, output = run_test_command(workspace)
    assert (code, last_line(output)) == (0, '9 passed, 0 failed'), output
    steps = [line.split()[2] for line in output.splitlines() if line.startswith('test: pytest tests/student')]
    assert sorted(steps) == ['tests/student/test_one.py', 'tests/student/test_two.py'], output


def test_a_workspace_without_packages_is_a_failure_not_an_empty_pass(workspace):
    shutil.rmtree(str(workspace / 'src'))
    (workspace / 'src').mkdir()
    code, output = run_test_command(workspace)
    assert code == 1 and 'found no package' in output, output
    assert 'passed' not in output


def test_an_unknown_package_is_refused_with_the_list_of_packages(workspace):
    code, output = run_test_command(workspace, 'turtlesimm')
    assert code == 2 and 'no package named turtlesimm here; the packages are: alpha beta' in output


def test_a_package_in_a_catkin_ignored_folder_is_not_a_package(workspace):
    add_package(workspace, 'src/old', 'old', {'helpers.py': 'HELP = 1\n'})
    write(str(workspace / 'src/old/CATKIN_IGNORE'), '')
    code, output = run_test_command(workspace)
    assert (code, last_line(output)) == (0, '5 passed, 0 failed'), output


def test_alone_jobs_never_overlap_and_the_others_run_beside_them_at_a_lower_priority(tmp_path):
    """run_test_jobs.py: `alone` jobs never overlap each other and keep the runner's priority; the
    others run beside them (two at a time with --jobs 2: one beside an alone job; none with a
    single core) at nice SHARED_NICE, which takes the core from them whenever the alone job wants it."""
    spans = tmp_path / 'spans.txt'
    job = 'echo "%s start $(date +%%s.%%N) $(nice)" >> {0}; %s; echo "%s end $(date +%%s.%%N)" >> {0}'.format(spans)
    # `a` starts beside `rates` and outlasts both alone jobs.
    outlast = 'until grep -q "more_rates end" {0}; do sleep 0.1; done; sleep 1'.format(spans)
    lines = ['%s\t0\t%s\t%s\n' % (name, sharing, job % (name, wait, name))
             for name, sharing, wait in [('a', 'shared', outlast), ('b', 'shared', 'sleep 0.3'),
                                         ('rates', 'alone', 'sleep 0.3'), ('more_rates', 'alone', 'sleep 0.3'),
                                         ('c', 'shared', 'sleep 0.3'), ('d', 'shared', 'sleep 0.3')]]
    result = subprocess.run(
        ['/usr/bin/python3', os.path.join(ROOT, 'tools', 'run_test_jobs.py'), '--jobs', '2',
         '--logs', str(tmp_path / 'logs'), '--times', str(tmp_path / 'times.txt'),
         '--failed-steps', str(tmp_path / 'failed.txt')],
        input=''.join(lines), stdout=subprocess.PIPE, universal_newlines=True, timeout=60)
    assert result.returncode == 0 and result.stdout.count('\n') == 7, result.stdout
    events, niceness = {}, {}
    for line in spans.read_text().splitlines():
        name, what, at = line.split()[:3]
        events[name, what] = float(at)
        if what == 'start':
            niceness[name] = int(line.split()[3])
    names = [name for name in 'abcd']

    def overlap(x, y):
        return events[x, 'start'] < events[y, 'end'] and events[y, 'start'] < events[x, 'end']
    assert not overlap('rates', 'more_rates'), events
    beside = [name for name in names if overlap(name, 'rates') or overlap(name, 'more_rates')]
    runner = os.getpriority(os.PRIO_PROCESS, 0)
    assert niceness == dict({'rates': runner, 'more_rates': runner},
                            **{name: max(10, runner) for name in names}), niceness
    if len(os.sched_getaffinity(0)) > 1:
        assert beside == ['a'], events  # beside each alone job, as many as --jobs leaves
        assert result.stdout.endswith('test: at most 2 steps ran side by side\n'), result.stdout
    else:
        assert beside == [], events
    assert any(overlap(x, y) for x in names for y in names if x < y), events  # two at a time after them
    assert (tmp_path / 'failed.txt').read_text() == ''


def load_run_test_jobs():
    spec = importlib.util.spec_from_file_location('run_test_jobs', os.path.join(ROOT, 'tools', 'run_test_jobs.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_idle_cores_of_two_proc_stat_samples(tmp_path):
    jobs = load_run_test_jobs()
    stat = tmp_path / 'stat'
    stat.write_text('cpu  100 0 50 800 50 0 0 0 0 0\ncpu0 50 0 25 400 25 0 0 0 0 0\n')
    assert jobs.cpu_sample(str(stat)) == (850, 1000)  # idle and iowait count as idle
    # Over 200 jiffies on 2 cores, 150 idle: 1.5 cores idle.
    assert jobs.idle_cores((850, 1000), (1000, 1200), 2) == 1.5
    assert jobs.idle_cores((850, 1000), (850, 1000), 2) == 0.0


class FakeMachine:
    """A clock and /proc/stat samples under the test's control: `idle` cores of 2 idle from now on."""
    def __init__(self):
        self.now, self.idle_jiffies, self.total_jiffies, self.idle = 0.0, 0, 0, 0.0

    def pass_seconds(self, seconds):
        self.now += seconds
        self.total_jiffies += int(200 * seconds)  # 2 cores, 100 jiffies a second each
        self.idle_jiffies += int(100 * self.idle * seconds)

    def sample(self):
        return self.idle_jiffies, self.total_jiffies


def test_auto_runs_two_then_more_while_the_idle_time_and_their_last_shares_leave_room():
    jobs = load_run_test_jobs()
    machine = FakeMachine()
    side_by_side = jobs.SideBySide('auto', 2, window=3.0, sample=machine.sample, clock=lambda: machine.now)
    assert side_by_side.spare([]) == side_by_side.spare([0.9]) == float('inf')
    machine.idle = 1.6
    machine.pass_seconds(1.0)
    assert side_by_side.spare([0.3, 0.3]) == 0.0  # idle, but not for a whole window yet
    machine.pass_seconds(2.5)
    # 1.6 cores idle less the headroom; the two running are planned at 0.3 each: 1.35 left.
    assert side_by_side.spare([0.3, 0.3]) == pytest.approx(1.35)
    side_by_side.started(0.3)
    machine.pass_seconds(0.5)
    # Half a second later the one just started is not in the idle time yet: its share counts as used.
    assert side_by_side.spare([0.3, 0.3, 0.3]) == pytest.approx(1.6 - 0.3 - 0.25)
    side_by_side.started(None)
    assert side_by_side.spare([0.3, 0.3, 0.3, None]) == pytest.approx(1.6 - 1.3 - 0.25)  # unknown: a core
    machine.pass_seconds(3.0)
    # A window later both are in the idle time (still 1.6 here); what is planned for them is left.
    assert side_by_side.spare([0.3, 0.3, 0.3]) == pytest.approx(2 - 0.9)
    # Two that computed in their last run (0.9 each): what they leave is what may start.
    assert side_by_side.spare([0.9, 0.9]) == pytest.approx(0.2)
    assert side_by_side.spare([None, 0.3]) == pytest.approx(0.7)  # unknown: a whole core
    assert side_by_side.spare([0.2] * jobs.SideBySide.AUTO_MOST) == 0.0  # never more than AUTO_MOST
    # A busy core beside the tests (another user's loop): nothing beyond the two starts.
    machine.idle = 0.3
    machine.pass_seconds(10.0)
    assert side_by_side.spare([0.3, 0.3]) < jobs.needs(0.0)
    assert side_by_side.spare([0.3]) == float('inf')


def test_after_the_rate_steps_up_to_six_run_while_a_quarter_core_is_idle():
    jobs = load_run_test_jobs()
    machine = FakeMachine()
    side_by_side = jobs.SideBySide('auto', 2, window=3.0, sample=machine.sample, clock=lambda: machine.now)
    machine.idle = 0.3
    machine.pass_seconds(3.5)
    # Five that computed (0.9 each, 4.5 cores planned): the shares no longer hold the next back.
    assert side_by_side.spare([0.9] * 5, rates_done=True) == float('inf')
    assert side_by_side.spare([0.9] * 5) == 0.0  # beside a rate step: never more than five
    assert side_by_side.spare([0.9, 0.9, 0.9]) < jobs.needs(0.0)  # nor beyond the plan
    side_by_side.started(0.3)
    side_by_side.started(None)
    # Two just started, not in the idle time yet: beside a rate step they are taken to use it (no
    # third starts); after the rate steps they are not, and the next starts at once.
    assert side_by_side.spare([0.1, 0.1, 0.1]) < jobs.needs(0.0)
    assert side_by_side.spare([0.9] * 4, rates_done=True) == float('inf')
    assert side_by_side.spare([0.1] * jobs.SideBySide.AUTO_MOST_AFTER_RATES, rates_done=True) == 0.0
    # Once the cores are busy (what was started computes), the next waits for idle time again.
    machine.idle = 0.2
    machine.pass_seconds(3.5)
    assert side_by_side.spare([0.9] * 4, rates_done=True) == 0.0
    # A loaded machine: no idle time, two run.
    machine.idle = 0.1
    machine.pass_seconds(10.0)
    assert side_by_side.spare([0.1, 0.1], rates_done=True) == 0.0
    assert side_by_side.spare([0.1], rates_done=True) == float('inf')


def test_the_next_job_starts_when_its_share_fits_and_none_passes_it():
    jobs = load_run_test_jobs()
    machine = FakeMachine()
    side_by_side = jobs.SideBySide('auto', 2, window=3.0, sample=machine.sample, clock=lambda: machine.now)
    known = {'builds': (90.0, 80.0), 'tour': (140.0, 35.0), 'grader': (50.0, 20.0), 'rates': (10.0, 3.0)}
    share = lambda label: jobs.cpu_share(known, label)
    waiting = [jobs.Job('builds', {0}, False, ''), jobs.Job('tour', {0}, False, ''),
               jobs.Job('new', {0}, False, '')]
    running = [jobs.Running(None, 'grader', {0}, False, None, 0.0, 'mark'),
               jobs.Running(None, 'rates', {0}, True, None, 0.0, 'mark')]
    assert jobs.next_job(waiting, running[:1], side_by_side, share) == 0  # two at least
    machine.idle = 1.0
    machine.pass_seconds(3.5)
    # Beside the rate step 0.75 of a core may start (planned: 2 - 0.4 - 0.3): not the builds (0.89),
    # and the tour (0.25), which would fit, does not pass them.
    assert jobs.next_job(waiting, running, side_by_side, share) is None
    # The same beside a shared step: the rate steps are over, the builds start (the idle time left).
    assert jobs.next_job(waiting, running[:1] + [running[1]._replace(alone=False)], side_by_side, share) == 0
    machine.pass_seconds(3.5)
    assert jobs.next_job(waiting[1:], running, side_by_side, share) == 0
    machine.pass_seconds(3.5)
    assert jobs.next_job(waiting[2:], running, side_by_side, share) is None  # unknown: a core


def test_a_job_that_ends_before_the_room_the_next_waits_for_comes_passes_it():
    """Backfilling: the grader's test (0.82 of a core) waits for the rate step (ends at 42 s) beside
    the page (a core until 65 s); a light step that ends by 42 s starts meanwhile, one that would
    end later does not, nor one that needs more than the idle time leaves."""
    jobs = load_run_test_jobs()
    machine = FakeMachine()
    side_by_side = jobs.SideBySide('auto', 2, window=3.0, sample=machine.sample, clock=lambda: machine.now)
    known = {'rates': (42.0, 14.7), 'page': (65.0, 63.7), 'grader': (49.0, 40.2), 'waits': (99.0, 8.0),
             'short': (35.0, 3.9), 'computes': (20.0, 14.0)}
    share = lambda label: jobs.cpu_share(known, label)
    wall = lambda label: known.get(label, (None,))[0]
    start = machine.now
    running = [jobs.Running(None, 'rates', {0}, True, None, start, 'mark'),
               jobs.Running(None, 'page', {0}, False, None, start, 'mark')]
    waiting = [jobs.Job(label, {0}, False, '') for label in ('grader', 'waits', 'computes', 'short')]
    machine.idle = 0.7
    machine.pass_seconds(5.0)
    # 0.45 of a core may start (idle 0.7 less the headroom); the room for the grader's comes at 42 s.
    assert jobs.room_comes(running, 0.82, 2, share, wall) == pytest.approx(start + 42.0)
    assert jobs.next_job(waiting, running, side_by_side, share, wall) == 3      # short: ends at 40 s
    assert jobs.next_job(waiting[:3], running, side_by_side, share, wall) is None   # waits: 104 s; computes: 0.7
    machine.pass_seconds(5.0)
    assert jobs.next_job(waiting[:2] + waiting[3:], running, side_by_side, share, wall) is None   # 45 s: too late
    # Room held by the idle time, not by the running jobs' shares: nothing passes (as before).
    assert jobs.room_comes(running[1:], 0.82, 2, share, wall) is None
    # A running job of unknown length: when the room comes is not known, nothing passes.
    unknown = [jobs.Running(None, 'new', {0}, False, None, start, 'mark'), running[0]]
    assert jobs.room_comes(unknown, 1.5, 2, share, wall) is None
    assert jobs.room_comes(unknown, 0.82, 2, share, wall) == pytest.approx(start + 42.0)  # it need not end


def test_a_fixed_number_of_jobs_never_grows():
    jobs = load_run_test_jobs()
    machine = FakeMachine()
    machine.idle = 2.0
    side_by_side = jobs.SideBySide(1, 2, sample=machine.sample, clock=lambda: machine.now)
    machine.pass_seconds(60.0)
    assert side_by_side.spare([]) == float('inf') and side_by_side.spare([0.1]) == 0.0


def test_a_first_run_starts_the_longest_steps_first_from_the_measured_seconds(tmp_path):
    """With no durations of its own yet (a fresh clone), the order comes from --first-times."""
    first_times = tmp_path / 'first.txt'
    first_times.write_text('# seconds<TAB>step\n5.0\tshort\n90.0\tlong\n30.0\tmiddle\n')
    lines = ''.join('%s\t0\tshared\techo %s\n' % (name, name) for name in ('short', 'middle', 'long', 'new'))
    result = subprocess.run(
        ['/usr/bin/python3', os.path.join(ROOT, 'tools', 'run_test_jobs.py'), '--jobs', '1',
         '--logs', str(tmp_path / 'logs'), '--times', str(tmp_path / 'times.txt'),
         '--first-times', str(first_times), '--failed-steps', str(tmp_path / 'failed.txt')],
        input=lines, stdout=subprocess.PIPE, universal_newlines=True, timeout=60)
    finished = [line.split()[1] for line in result.stdout.splitlines()[:-1]]
    assert finished == ['new', 'long', 'middle', 'short'], result.stdout  # unknown steps first
    assert 'long' in (tmp_path / 'times.txt').read_text()  # the next run uses its own times


def test_the_steps_that_hold_the_most_core_seconds_start_first(tmp_path):
    """A step that waits (98 s at a tenth of a core: a quarter of a core held) comes after one that
    computes for 65 s, and one of unknown CPU is taken to use a whole core."""
    times = tmp_path / 'times.txt'
    times.write_text('98.0\t9.0\twaits\n65.0\t70.0\tcomputes\n30.0\t-\tunknown_cpu\n20.0\t5.0\tshort\n')
    lines = ''.join('%s\t0\tshared\techo %s\n' % (name, name) for name in ('short', 'waits', 'unknown_cpu', 'computes'))
    result = subprocess.run(
        ['/usr/bin/python3', os.path.join(ROOT, 'tools', 'run_test_jobs.py'), '--jobs', '1',
         '--logs', str(tmp_path / 'logs'), '--times', str(times), '--failed-steps', str(tmp_path / 'failed.txt')],
        input=lines, stdout=subprocess.PIPE, universal_newlines=True, timeout=60)
    finished = [line.split()[1] for line in result.stdout.splitlines()[:-1]]
    assert finished == ['computes', 'unknown_cpu', 'waits', 'short'], result.stdout


def test_beside_an_alone_job_the_others_start_as_its_share_and_the_idle_time_leave_room(tmp_path):
    """While an alone job runs, the next alone job waits, and shared jobs start as they would
    otherwise (SideBySide), the alone job's share of a core in its last run counted with theirs;
    with --jobs 1 or on a single core, nothing starts beside it."""
    jobs = load_run_test_jobs()
    times = tmp_path / 'times.txt'
    times.write_text('140.0\t35.0\ttour\n40.0\t6.0\tteleop\n90.0\t80.0\tbuilds\n20.0\tlistener\n'
                     '12.0\t3.0\trates\n')
    known = jobs.read_times(str(times))
    assert known['tour'] == (140.0, 35.0) and known['listener'] == (20.0, None)  # the older form
    share = lambda label: jobs.cpu_share(known, label)
    assert share('tour') == 0.25 and share('listener') is None and share('unknown') is None
    machine = FakeMachine()
    side_by_side = jobs.SideBySide('auto', 2, sample=machine.sample, clock=lambda: machine.now)
    waiting = [jobs.Job('more_rates', {0}, True, ''), jobs.Job('builds', {0}, False, ''),
               jobs.Job('teleop', {0}, False, '')]
    alone = jobs.Running(None, 'rates', {0}, True, None, 0.0, 'mark')
    tour = jobs.Running(None, 'tour', {0}, False, None, 0.0, 'mark')
    # The next alone job waits for this one; a shared one starts beside it (two at least).
    assert jobs.next_job(waiting, [alone], side_by_side, share) == 1
    assert jobs.next_job(waiting, [tour], side_by_side, share) == 0  # beside shared jobs, at once
    # Beyond two, the idle time decides: 1.2 cores idle, less the headroom, and planned 2 - 0.25
    # for the alone job, 0.25 for the tour: 0.95 of a core, enough for the builds (0.89).
    machine.idle = 1.2
    machine.pass_seconds(3.5)
    assert jobs.next_job(waiting, [alone, tour], side_by_side, share) == 1
    machine.idle = 0.8
    machine.pass_seconds(3.5)
    assert jobs.next_job(waiting, [alone, tour], side_by_side, share) is None  # 0.55: the builds wait,
    assert jobs.next_job(waiting[:1] + waiting[2:], [alone, tour], side_by_side, share) == 1  # not the teleop
    for one_at_a_time in (jobs.SideBySide(1, 2), jobs.SideBySide('auto', 1)):
        assert jobs.next_job(waiting, [alone], one_at_a_time, share) is None
        assert jobs.next_job(waiting, [tour], one_at_a_time, share) is None  # it waits for the tour
        assert jobs.next_job(waiting, [], one_at_a_time, share) == 0
    # The next run reads the CPU seconds this run writes.
    lines = 'tour\t0\tshared\tsleep 0.2\nrates\t0\talone\tsleep 0.1\n'
    subprocess.run(['/usr/bin/python3', os.path.join(ROOT, 'tools', 'run_test_jobs.py'), '--jobs', '2',
                    '--logs', str(tmp_path / 'logs'), '--times', str(times),
                    '--failed-steps', str(tmp_path / 'failed.txt')],
                   input=lines, stdout=subprocess.PIPE, universal_newlines=True, timeout=60, check=True)
    again = jobs.read_times(str(times))
    assert again['tour'][0] >= 0.2 and 0.0 <= again['tour'][1] < again['tour'][0], again
    assert again['listener'] == (20.0, None)


def test_jobs_get_ctrl_c_back_when_the_test_command_runs_in_the_background(tmp_path):
    """A background shell ignores SIGINT and SIGQUIT, and its programs inherit that; the jobs do not."""
    job, runner = tmp_path / 'job.txt', tmp_path / 'runner.txt'

    def as_a_background_job():
        for number in (signal.SIGINT, signal.SIGQUIT):
            signal.signal(number, signal.SIG_IGN)

    result = subprocess.run(
        ['/usr/bin/python3', os.path.join(ROOT, 'tools', 'run_test_jobs.py'), '--jobs', '1',
         '--logs', str(tmp_path / 'logs'), '--times', str(tmp_path / 'times.txt'),
         '--failed-steps', str(tmp_path / 'failed.txt')],
        input='status\t0\tshared\tcat /proc/self/status > %s; cat /proc/$PPID/status > %s\n' % (job, runner),
        stdout=subprocess.PIPE, universal_newlines=True, timeout=60, preexec_fn=as_a_background_job)
    assert result.returncode == 0, result.stdout
    assert {signal.SIGINT, signal.SIGQUIT} <= ignored_signals(runner.read_text())  # as it was started
    assert not {signal.SIGINT, signal.SIGQUIT} & ignored_signals(job.read_text())


def test_a_step_named_to_run_alone_that_is_no_step_fails_a_whole_run(workspace):
    """tools/test-alone-steps.txt: a step renamed or moved would run beside the others unseen."""
    write(str(workspace / 'tools/test-alone-steps.txt'),
          '# a comment\npytest tests\n\nrostest gone/test/renamed.test\n')
    code, output = run_test_command(workspace)
    assert code == 1, output
    assert "FAILED: tools/test-alone-steps.txt names 'rostest gone/test/renamed.test', which is no step of this run" \
        in output
    assert 'pytest tests' not in [line.split("'")[1] for line in output.splitlines() if 'names \'' in line]
    # A run of some packages has fewer steps: nothing to say then.
    code, output = run_test_command(workspace, 'alpha')
    assert (code, last_line(output)) == (0, '2 passed, 0 failed'), output


def test_the_tests_that_need_root_run_only_as_root_and_a_line_says_so_elsewhere(workspace):
    """tests/test_user_reaper.py (in the quick step) and tests/network/test_two_hosts.py (a step of its
    own) run as root; for an ordinary user (the Docker image's) each is named as not run, nothing else."""
    write(str(workspace / 'tests/test_user_reaper.py'), 'def test_reaper():\n    assert False, "ran"\n')
    write(str(workspace / 'tests/network/test_two_hosts.py'), 'def test_two_hosts():\n    assert False, "ran"\n')
    write(str(workspace / 'tools/test-alone-steps.txt'), 'pytest tests/network/test_two_hosts.py\n')
    for uid, closing in (('1000', '5 passed, 0 failed'), ('0', '5 passed, 2 failed')):
        write(str(workspace / 'tools/fake_bin/id'), '#!/bin/bash\necho %s\n' % uid, 0o755)   # after env.sh
        code, output = run_test_command(workspace)
        assert last_line(output) == closing, output
        said = [line for line in output.splitlines() if 'needs root' in line]
        if uid == '0':
            assert code == 1 and said == [] and 'names \'' not in output, output
        else:
            assert code == 0 and said == ['test: tests/test_user_reaper.py needs root: not run here',
                                          'test: tests/network/test_two_hosts.py needs root: not run here'], output


def test_the_steps_ros_home_is_the_runs_own_and_the_next_run_replaces_it(workspace):
    # The steps' logs and pictures stay with the run's logs, not in the user's ~/.ros.
    add_package(workspace, 'src/gamma', 'gamma', {'test_gamma.py': (
        'import os\n\n\ndef test_ros_home():\n'
        '    home = os.environ["ROS_HOME"]\n'
        '    assert not os.path.exists(os.path.join(home, "left_by_the_last_run"))\n'
        '    os.makedirs(home, exist_ok=True)\n'
        '    open(os.path.join(home, "left_by_the_last_run"), "w").close()\n')})
    for _ in range(2):
        code, output = run_test_command(workspace, 'gamma')
        assert (code, last_line(output)) == (0, '1 passed, 0 failed'), output
    assert (workspace / 'build/test_logs/ros_home/left_by_the_last_run').exists()
    assert not (workspace.parent / '.ros').exists()
