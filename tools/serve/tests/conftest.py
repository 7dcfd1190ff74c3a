"""Fixtures: `tnvctl --emu serve --port 0` (the friction-free reference table)
with its own parameter file, and
Debian's chromium, headless, driven by python3-selenium."""

import os
import re
import shutil
import signal
import subprocess
import time

import pytest

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


class PageUrl(str):
    """The printed URL, with its parts: base (http://127.0.0.1:PORT), host
    (127.0.0.1:PORT), secret, and the server's audit file."""

    def __new__(cls, url, audit):
        self = super().__new__(cls, url)
        self.base, self.secret = url.split("/?token=")
        self.host = self.base.split("://", 1)[1]
        self.audit = audit
        return self


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """The page's URL as printed by a running `tnvctl --emu serve --port 0`:
    http://127.0.0.1:PORT/?token=SECRET (the secret is new at each start)."""
    exe = os.environ.get("TNVCTL_EXE")
    if not exe:
        pytest.fail("TNVCTL_EXE is not set (ctest sets it to the built tnvctl)")
    node_dir = tmp_path_factory.mktemp("node")
    storage = node_dir / "node.params"
    audit = node_dir / "audit.jsonl"
    # The reference table with friction off: the Bode view's measurement is
    # then the linear loop its model describes (docs/frequency-response.md).
    scenario = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tests", "data", "tables",
                            "no-friction.toml")
    proc = subprocess.Popen([exe, "--emu", "--emu-scenario", scenario, "--emu-storage", str(storage), "serve",
                             "--port", "0", "--audit", str(audit),
                             # Two headless browsers on a busy 2-core machine may stall a page for longer than
                             # the default 0.3 s: closing a tab is seen at once (its stream ends), and the
                             # 0.3 s heartbeat rule is DeadmanTest's (test_serve).
                             "--deadman-ms", "3000"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    match = re.search(r"(http://\S+/\?token=[0-9a-f]{64})\s", line)
    if not match:
        proc.kill()
        pytest.fail(f"tnvctl serve printed no URL with its secret: {line!r} {proc.stderr.read()!r}")
    yield PageUrl(match.group(1), audit)
    proc.send_signal(signal.SIGINT)
    try:
        assert proc.wait(timeout=10) == 0, proc.stderr.read()
    except subprocess.TimeoutExpired:
        proc.kill()
        pytest.fail("tnvctl serve did not end within 10 s of SIGINT")


def _chromium_or_skip():
    if not (os.path.exists(CHROMIUM) and os.path.exists(CHROMEDRIVER)):
        pytest.skip("Debian's chromium and chromium-driver are not installed (scripts/install-deps.sh installs them)")
    try:
        from selenium import webdriver  # noqa: F401
    except ImportError:
        pytest.skip("python3-selenium is not installed (scripts/install-deps.sh installs it)")


def _start_browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--window-size=1400,1000",
                "--hide-scrollbars", "--force-device-scale-factor=1"):
        options.add_argument(arg)
    browser = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    # A hung page fails the test instead of the ctest timeout (900 s); 120 s,
    # not 30: a page load took longer than 30 s beside a two-job build and
    # the two-job suite on the 2-core machine (the renderer did not answer).
    browser.set_page_load_timeout(120)
    browser.set_script_timeout(120)
    return browser


@pytest.fixture(scope="module")
def browsers():
    """Opens headless chromium windows on demand: browsers() -> a new one."""
    _chromium_or_skip()
    opened = []

    def open_one():
        opened.append(_start_browser())
        return opened[-1]

    open_one.opened = opened  # the windows open now (a test that closes one removes it)
    yield open_one
    for b in opened:
        b.quit()


def wait_for(condition, timeout_s=30.0, what="condition"):
    """Polls `condition` until it returns a true value; fails naming `what`."""
    from selenium.common.exceptions import NoSuchElementException, StaleElementReferenceException, TimeoutException

    deadline = time.monotonic() + timeout_s
    while True:
        try:
            value = condition()
        except (NoSuchElementException, StaleElementReferenceException):
            value = None  # the page is redrawing that part: look again
        except TimeoutException:
            value = None  # a starved renderer did not answer the script in time: ask again until the deadline
        if value:
            return value
        if time.monotonic() > deadline:
            pytest.fail(f"{what} not seen within {timeout_s} s")
        time.sleep(0.05)


@pytest.fixture
def screenshot():
    """Saves a PNG of a browser window into $TNV_SCREENSHOT_DIR (when set)."""
    target = os.environ.get("TNV_SCREENSHOT_DIR")

    def take(browser, name):
        if target:
            os.makedirs(target, exist_ok=True)
            browser.save_screenshot(os.path.join(target, name + ".png"))

    return take


def pytest_report_header():
    return f"chromium: {shutil.which('chromium') or 'not installed'}"
