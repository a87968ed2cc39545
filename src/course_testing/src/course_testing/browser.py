"""A real browser for tests and benchmarks: Debian's chromium, driven by chromedriver (selenium),
headless, with pictures of page elements as RGB arrays."""
import io
import os
import shutil
import tempfile

import numpy as np

CHROMIUM = '/usr/bin/chromium'
CHROMEDRIVER = '/usr/bin/chromedriver'


def can_run_browser():
    return os.path.exists(CHROMIUM) and shutil.which(CHROMEDRIVER) is not None


def start_browser(width=1300, height=1000):
    """A headless chromium (selenium WebDriver). quit() it when done: that stops chromium too, and
    removes the temporary folder chromium was given (chromium leaves its socket's folder behind
    when chromedriver ends it: one in /tmp for each browser a test started)."""
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
    # In the system's temporary folder, not under a TMPDIR of the caller's: a socket's path must
    # stay under 108 characters.
    scratch = tempfile.mkdtemp(prefix='course-browser-', dir='/tmp')
    try:
        browser = webdriver.Chrome(service=Service(executable_path=CHROMEDRIVER,
                                                   env=dict(os.environ, TMPDIR=scratch)), options=options)
    except BaseException:
        shutil.rmtree(scratch, ignore_errors=True)
        raise
    quit_browser = browser.quit

    def quit_and_clean():
        try:
            quit_browser()
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
    browser.quit = quit_and_clean
    return browser


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
