"""The tour's own master: a master that another program started on the tour's port first is not
taken for the tour's (the port was free when chosen, not reserved)."""
import os

import pytest

from course_testing.processes import other_master
from course_tour import session as tour_session


def test_a_master_already_on_the_port_is_not_the_tours(tmp_path, monkeypatch):
    with other_master() as port:
        monkeypatch.setattr(tour_session, 'free_port', lambda: port)
        for name in ('ROS_MASTER_URI', 'COURSE_TOUR'):   # what the session sets in os.environ, restored
            monkeypatch.setenv(name, os.environ.get(name, ''))
        session = tour_session.Session(str(tmp_path))
        with pytest.raises(RuntimeError) as failure:
            session.__enter__()
        assert str(failure.value).startswith('roscore ended before its master answered:\n')
        assert 'another roscore/master is already running' in str(failure.value)
        session._master.stop()
