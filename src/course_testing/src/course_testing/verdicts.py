"""A grading's sentences compared from run to run: robots move in real time, so a stop reads
0.446 m one time and 0.451 m the next; what must not change is the points and what each says."""
import re

FIGURE = re.compile(r'-?\d+(\.\d+)?')


def masked_figures(text):
    """The sentence with every number in it as '#'."""
    return FIGURE.sub('#', text)
