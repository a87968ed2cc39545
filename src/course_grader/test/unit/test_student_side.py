"""The student's side of a grading: every program of it is the first the kernel's out-of-memory
killer takes, and the trusted side keeps its own score (docs/grading.md, isolation)."""
from course_grader import grading_session
from course_grader.grading_session import StudentSide


def own_score():
    with open('/proc/self/oom_score_adj') as score:
        return score.read().strip()


def test_what_the_student_side_runs_and_starts_is_killed_first_when_memory_runs_out(tmp_path):
    side = StudentSide(None, str(tmp_path))
    assert side.run(['cat', '/proc/self/oom_score_adj'], 10) == b'1000\n'
    started = side.start(['sh', '-c', 'cat /proc/self/oom_score_adj; cat /proc/$$/oom_score_adj'],
                         str(tmp_path / 'started.log'))
    assert started.process.wait(10) == 0
    started.stop(5)
    # The program and what it starts in turn.
    assert started.lines == ['1000', '1000']
    assert own_score() != '1000'


def test_without_proc_the_student_side_still_runs(tmp_path, monkeypatch):
    # Gradescope's chroot has no /proc: choom could not set the score, so it is not used there.
    monkeypatch.setattr(grading_session, 'OOM_SCORE', str(tmp_path / 'no_proc' / 'oom_score_adj'))
    side = StudentSide(None, str(tmp_path))
    assert side.run(['cat', '/proc/self/oom_score_adj'], 10).decode().strip() == own_score()
