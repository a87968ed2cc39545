"""tools/setup.sh decides, before installing anything, whether this machine can take the course.

The machine is named by a fake os-release file (COURSE_OS_RELEASE), so these tests are the same on
any host and never install a package.
"""
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SETUP = os.path.join(ROOT, 'tools', 'setup.sh')
REFUSED = 3

UBUNTU = 'PRETTY_NAME="Ubuntu 22.04.4 LTS"\nNAME="Ubuntu"\nID=ubuntu\nID_LIKE=debian\nVERSION_CODENAME=jammy\n'
BULLSEYE = 'PRETTY_NAME="Debian GNU/Linux 11 (bullseye)"\nID=debian\nVERSION_CODENAME=bullseye\n'
TRIXIE = 'PRETTY_NAME="Debian GNU/Linux 13 (trixie)"\nID=debian\nVERSION_ID="13"\nVERSION_CODENAME=trixie\n'
BOOKWORM = "PRETTY_NAME='Debian GNU/Linux 12 (bookworm)'\nID=debian\nVERSION_CODENAME=bookworm\n"


def run_setup(tmp_path, os_release, *args, package_list=None):
    """Runs tools/setup.sh ARGS on a machine named by os_release (None: no os-release file at all)."""
    env = dict(os.environ, COURSE_OS_RELEASE=str(tmp_path / 'os-release'),
               CATKIN_BUILD_BASE=str(tmp_path / 'build-base'))
    env.pop('COURSE_SKIP_INSTALL', None)
    if os_release is not None:
        (tmp_path / 'os-release').write_text(os_release)
    if package_list is not None:
        (tmp_path / 'packages.txt').write_text(package_list)
        env['COURSE_PACKAGE_LIST'] = str(tmp_path / 'packages.txt')
    return subprocess.run([SETUP] + list(args), env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          universal_newlines=True, timeout=60)


def assert_refused_in_one_sentence(result, *words):
    assert result.returncode == REFUSED, result
    assert result.stdout == ''   # nothing installed, nothing built
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    for word in words + ('nothing was installed', 'docs/student-docker.md'):
        assert word in lines[0], lines[0]


def test_ubuntu_is_told_to_use_docker_and_nothing_is_installed_or_built(tmp_path):
    result = run_setup(tmp_path, UBUNTU)
    assert_refused_in_one_sentence(result, 'Ubuntu 22.04.4 LTS', 'Debian 13 trixie', 'Debian 12 bookworm')
    assert not (tmp_path / 'build-base').exists()


def test_an_older_debian_is_refused_before_installing(tmp_path):
    assert_refused_in_one_sentence(run_setup(tmp_path, BULLSEYE, '--install-only'), 'Debian GNU/Linux 11 (bullseye)')


def test_a_machine_without_os_release_is_refused(tmp_path):
    assert_refused_in_one_sentence(run_setup(tmp_path, None, '--check'), 'unknown system')


def test_each_suite_gets_the_common_packages_and_its_own(tmp_path):
    package_list = '# comment\ng++\n\ntrixie: only-on-trixie\nbookworm:only-on-bookworm   # why\nrviz\n'
    trixie = run_setup(tmp_path, TRIXIE, '--packages', package_list=package_list)
    assert trixie.returncode == 0, trixie.stderr
    assert trixie.stdout.split() == ['g++', 'only-on-trixie', 'rviz']
    bookworm = run_setup(tmp_path, BOOKWORM, '--packages', package_list=package_list)
    assert bookworm.stdout.split() == ['g++', 'only-on-bookworm', 'rviz']


def test_the_real_package_list_differs_between_the_suites_only_where_it_says_so(tmp_path):
    trixie = run_setup(tmp_path, TRIXIE, '--packages').stdout.split()
    bookworm = run_setup(tmp_path, BOOKWORM, '--packages').stdout.split()
    assert 'python3-rospy' in trixie and 'python3-rospy' in bookworm and len(trixie) > 40
    with open(os.path.join(ROOT, 'tools', 'debian-packages.txt')) as stream:
        marked = [line.split('#')[0].split() for line in stream]
    only = {suite: {words[1] for words in marked if len(words) == 2 and words[0] == suite + ':'}
            for suite in ('trixie', 'bookworm')}
    assert set(bookworm) - set(trixie) == only['bookworm'] and set(trixie) - set(bookworm) == only['trixie']


def test_a_debian_whose_archive_lacks_a_package_names_it_and_installs_nothing(tmp_path):
    # python3 is installed wherever this test runs; the other package exists in no archive.
    result = run_setup(tmp_path, TRIXIE, '--check', package_list='python3\ncourse-no-such-package\n')
    assert_refused_in_one_sentence(result, 'Debian trixie', 'course-no-such-package')
    assert 'python3 ' not in result.stderr
