import subprocess
import sys

import numpy as np
from PIL import Image

from course_testing.screen import VirtualScreen, can_make_screens, red_pixels
from course_common.waiting import wait_until

RED_WINDOW = """
import tkinter
window = tkinter.Tk()
window.title('probe')
window.geometry('100x80')
window.configure(background='red')
window.mainloop()
"""


def test_the_tools_for_screens_are_installed():
    assert can_make_screens()


def test_a_virtual_screen_is_black_and_of_the_size_asked(tmp_path):
    with VirtualScreen(320, 200) as screen:
        assert screen.display.startswith(':')
        assert screen.environment({'A': '1'}) == {'A': '1', 'DISPLAY': screen.display}
        picture = np.asarray(Image.open(screen.screenshot(str(tmp_path / 'screen.png'))).convert('RGB'))
    assert picture.shape == (200, 320, 3)
    assert picture.max() == 0


def test_a_window_is_found_by_its_title_and_shot_alone(tmp_path):
    with VirtualScreen(320, 200) as screen:
        assert screen.window_id('probe') is None
        window = subprocess.Popen([sys.executable, '-c', RED_WINDOW], env=screen.environment(),
                                  start_new_session=True)
        try:
            found = wait_until(lambda: screen.window_id('probe'), 20, what='the probe window')
            shot = Image.open(screen.screenshot(str(tmp_path / 'window.png'), window=found))
            picture = np.asarray(shot.convert('RGB'))
        finally:
            window.kill()  # Tk's mainloop would notice a SIGINT only at its next event
            window.wait()
    assert picture.shape == (80, 100, 3)
    assert (picture == (255, 0, 0)).all(axis=2).mean() > 0.9


def test_red_pixels_counts_only_laser_red(tmp_path):
    picture = np.zeros((10, 20, 3), dtype=np.uint8)
    picture[2, :7] = (255, 0, 0)
    picture[5, :3] = (230, 40, 30)
    picture[7, :] = (255, 120, 120)  # pink is not red
    Image.fromarray(picture).save(str(tmp_path / 'red.png'))
    assert red_pixels(str(tmp_path / 'red.png')) == 10
