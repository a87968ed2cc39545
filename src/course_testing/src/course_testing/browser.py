"""A real browser for tests and benchmarks: Debian's chromium, driven by chromedriver (selenium),
headless, with pictures of page elements as RGB arrays."""
import io
import os
import shutil

import numpy as np

CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'


def can_run_browser():
    return os.path.exists(CHROMIUM) and shutil.which(CHROMEDRIVER) is not None


def start_browser(width=1300, height=1000):
    """A headless chromium (selenium WebDriver). quit() it when done: that stops chromium too."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    # No sandbox: it needs user namespaces, which a Docker container's seccomp profile refuses;
    # this browser only ever opens our own page on loopback.
    for argument in ('--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--disable-gpu',
                     '--window-size=%d,%d' % (width, height), '--force-device-scale-factor=1',
                     '--disable-background-timer-throttling', '--disable-renderer-backgrounding'):
        options.add_argument(argument)
    return webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER), options=options)


def element_pixels(element, border=1):
    """What the screen shows of a page element (a canvas), as an RGB array, without its border."""
    from PIL import Image
    image = np.array(Image.open(io.BytesIO(element.screenshot_as_png)).convert('RGB'))
    if border:
        image = image[border:-border, border:-border]
    return image


def save_pixels(pixels, path):
    from PIL import Image
    Image.fromarray(pixels, 'RGB').save(path)
