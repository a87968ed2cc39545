import pytest

from course_tour.labs import LABS
from course_tour.main import parse_args


def test_no_lab_named_means_every_lab():
    assert parse_args([]).labs == []


def test_a_lab_can_be_chosen_by_name():
    name = LABS[-1].name
    assert parse_args([name]).labs == [name]


def test_an_unknown_lab_is_refused_with_the_list_of_labs(capsys):
    with pytest.raises(SystemExit) as stop:
        parse_args(['no_such_lab'])
    assert stop.value.code == 2
    error = capsys.readouterr().err
    assert 'unknown lab no_such_lab' in error and LABS[0].name in error


def test_lab_names_are_unique_and_short():
    names = [lab.name for lab in LABS]
    assert len(names) == len(set(names))
    assert all(len(name) <= 8 and name.isidentifier() for name in names)
