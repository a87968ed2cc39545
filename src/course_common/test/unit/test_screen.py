import numpy as np
from PIL import Image

from course_common.screen import VirtualScreen, can_make_screens


def test_the_tools_for_screens_are_installed():
    assert can_make_screens()


def test_a_virtual_screen_is_black_and_of_the_size_asked(tmp_path):
    with VirtualScreen(320, 200) as screen:
        assert screen.display.startswith(':')
        assert screen.environment({'A': '1'}) == {'A': '1', 'DISPLAY': screen.display}
        picture = np.asarray(Image.open(screen.screenshot(str(tmp_path / 'screen.png'))).convert('RGB'))
    assert picture.shape == (200, 320, 3)
    assert picture.max() == 0
