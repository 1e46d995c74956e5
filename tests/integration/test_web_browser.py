# SPDX-License-Identifier: Apache-2.0
"""The bench page of atv312d (docs/web.md) in a real browser: Debian's chromium, headless, driven by
selenium, against the daemon's own HTTP server (`--http`, `--http-actions`) on real SocketCAN.

- The page loads with no console error and shows one tile per drive.
- A master on the bus (NMT start, the target velocity by SDO, the CiA 402 sequence by RPDO1)
  starts a drive: its tile's display goes nSt -> rdY -> the output frequency, its trend rises
  along the ramp with the state changes marked.
- A fault injected by a click on the drive's page is on the bus as its EMCY, frame for frame, and
  on the tile as the fault code with the ERR LED's double flash.
- The same for a DeviceNet drive (`--devicenet`) polled by dnscan: the fault is the poll
  response's Faulted bit.

Its own ctest entry (integration_web_browser) boots User-Mode Linux with 2 GB (a headless chromium
needs it; the rest of the suite keeps 512 MB). One browser for the whole file: its first page load
takes about 20 s in the guest. Every wait has a deadline (WebDriverWait, a frame, a dnscan line).
WEB_SCREENSHOTS=DIR saves the screenshots of docs/web.md into DIR."""

import os
import queue
import re
from pathlib import Path

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

from conftest import NMT_START
from test_devicenet import Poller
from test_http import http_port

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
# The first page load of a browser inside User-Mode Linux takes about 20 s; later ones far less.
LOAD_TIMEOUT = 90
# How long a change on the bus may take to reach the page: the state events come up to 4 times a
# second, and the guest's browser is slow.
PAGE_TIMEOUT = 15
# From Operation enabled to 1500 rpm: the default ramp (ACC 3 s) with room for a loaded guest.
RAMP_TIMEOUT = 20
SCREENSHOTS = os.environ.get("WEB_SCREENSHOTS")

TOKEN = "bench-s3cret"
NODE = 4
MAC_ID = 25
RPM_1500_DISPLAY = "50.0"  # the output frequency at 1500 rpm: 50.0 Hz (the motor's nominal)
RPM_1200_DISPLAY = "40.0"
# The scanner's poll period, and how long it awaits each answer: the guest has one CPU, which the
# browser shares with the daemon and dnscan, so the polled connection gets a watchdog of about 1 s
# (4 x the expected packet rate) where test_devicenet.py's gets 416 ms.
POLL_MS = 250
POLL_ANSWER_MS = 3000


@pytest.fixture(scope="module")
def chromium(tmp_path_factory):
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                     "--window-size=1280,1150", f"--user-data-dir={tmp_path_factory.mktemp('chromium')}"):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.set_page_load_timeout(LOAD_TIMEOUT)
    yield driver
    driver.quit()


@pytest.fixture
def browser(chromium):
    """The browser, left on a blank page after the test, before its daemon stops: its event stream
    closed, nothing of the page running while the next test's daemon starts (the guest has one
    CPU)."""
    yield chromium
    chromium.get("about:blank")


class Page:
    """The bench page in the browser, with the waits the tests need."""

    def __init__(self, driver, port):
        self.driver = driver
        self.url = f"http://127.0.0.1:{port}/"

    def load(self):
        # What the browser logged before, such as the event stream of the previous test's daemon
        # ending when the daemon stopped, is not this page's.
        self.driver.get("about:blank")
        self.driver.get_log("browser")
        self.driver.get(self.url)
        self.wait(lambda d: d.execute_script("return document.body.dataset.ready === 'true'"), LOAD_TIMEOUT,
                  "the page did not show the bench")
        self.wait(lambda d: d.find_element(By.ID, "link").get_attribute("data-live") == "true", PAGE_TIMEOUT,
                  "the state events did not start")

    def wait(self, condition, timeout=PAGE_TIMEOUT, what="condition"):
        return WebDriverWait(self.driver, timeout, poll_frequency=0.1).until(condition, message=what)

    def console_errors(self):
        return [e for e in self.driver.get_log("browser") if e["level"] == "SEVERE"]

    def tile(self, node, where="#tiles"):
        return self.driver.find_element(By.CSS_SELECTOR, f"{where} .tile[data-node='{node}']")

    def drive_tile(self):
        return self.driver.find_element(By.CSS_SELECTOR, "#drive-tile .tile")

    def wait_tile(self, tile, timeout=PAGE_TIMEOUT, **wanted):
        """Waits until the tile's data attributes (display, fault, cia402) have the wanted values."""
        def matches(_):
            return all(tile.get_attribute(f"data-{k}") == v for k, v in wanted.items())
        self.wait(matches, timeout, f"tile: no {wanted}; has display {tile.get_attribute('data-display')!r}, "
                                    f"fault {tile.get_attribute('data-fault')!r}")

    def field(self, tile, name):
        return tile.find_element(By.CSS_SELECTOR, f"dd[data-field='{name}']").text

    def led(self, tile, name):
        """(aria-label, CSS animation name, its duration) of an LED of the tile: the animation of
        its lit layer."""
        led = tile.find_element(By.CSS_SELECTOR, f".led[data-led='{name}']")
        style = self.driver.execute_script(
            "const s = getComputedStyle(arguments[0], '::after'); return [s.animationName, s.animationDuration];",
            led)
        return (led.get_attribute("aria-label"), *style)

    def segments(self, tile):
        """The lit segments of each digit of the tile's display: 'ceg' for n, '.' for the point."""
        return self.driver.execute_script(
            "return [...arguments[0].querySelectorAll('svg.seven-segment > g')].map((digit) =>"
            " [...digit.querySelectorAll('.on')].map((s) => s.dataset.segment === 'dp' ? '.' : s.dataset.segment)"
            ".join(''));", tile)

    def trend(self, node):
        return self.driver.execute_script("return window.atv312d.trend(arguments[0]);", node)

    def open_drive(self, node):
        self.tile(node).find_element(By.CSS_SELECTOR, ".tile-title a").click()
        self.wait(lambda d: d.find_element(By.ID, "drive-view").is_displayed(), what="the drive's page")

    def click_fault(self, code):
        Select(self.driver.find_element(By.ID, "fault-code")).select_by_value(code)
        self.driver.find_element(By.CSS_SELECTOR, "button[data-command^='fault ']").click()

    def give_token(self, token):
        form = self.driver.find_element(By.ID, "token-form")
        assert form.is_displayed(), "the page does not ask for the token"
        self.driver.find_element(By.ID, "token").send_keys(token)
        form.find_element(By.CSS_SELECTOR, "button[type='submit']").click()
        self.wait(lambda _: not form.is_displayed(), what="the token form closed")

    def reply(self):
        """The one-line answer to the last command, once it came."""
        reply = self.driver.find_element(By.ID, "reply")
        self.wait(lambda _: reply.get_attribute("data-ok") in ("true", "false"), what="an answer to the command")
        return reply.text

    def screenshot(self, name):
        """The page down to the end of its content, into WEB_SCREENSHOTS/name when it is set."""
        if SCREENSHOTS:
            self.driver.find_element(By.TAG_NAME, "body").screenshot(str(Path(SCREENSHOTS) / name))


def drain(lines):
    out = []
    while True:
        try:
            out.append(lines.get_nowait())
        except queue.Empty:
            return out


def assert_trend_rises(page, node, top_rpm):
    """The trend went from standstill up the ramp to top_rpm, sample by sample, never down."""
    page.wait(lambda _: any(s["speed"] >= top_rpm for s in page.trend(node)["samples"]), RAMP_TIMEOUT,
              f"the trend of {node} did not reach {top_rpm} rpm")
    speeds = [s["speed"] for s in page.trend(node)["samples"]]
    top = next(i for i, v in enumerate(speeds) if v >= top_rpm)
    assert 0 in speeds[:top], f"the trend shows no standstill before the ramp: {speeds}"
    start = max(i for i in range(top) if speeds[i] == 0)
    ramp = speeds[start:top + 1]
    assert ramp == sorted(ramp), f"the speed went down on the way up: {ramp}"
    assert len([v for v in ramp if 0 < v < top_rpm]) >= 2, f"no ramp in the trend, a jump: {ramp}"


def test_canopen_bench_started_by_a_master_and_a_fault_by_click(bus, dump, start_daemon, tmp_path, browser):
    token = tmp_path / "token"
    token.write_text(f"{TOKEN}\n")
    daemon = start_daemon(bus, "--node-id", NODE, "--node-id", 5, "--model", "atv31", "--node-id", 6, "--model",
                          "atv58", "--http", "0", "--http-actions", "--http-token", token, padded_ids=[6])
    page = Page(browser, http_port(daemon))
    page.load()
    assert page.console_errors() == []
    assert [t.get_attribute("data-node") for t in browser.find_elements(By.CSS_SELECTOR, "#tiles .tile")] == [
        "4", "5", "6"]
    tile = page.tile(NODE)
    assert tile.find_element(By.CSS_SELECTOR, ".tile-title").text == "Node 4 · ATV312"
    page.wait_tile(tile, display="nSt", cia402="Switch on disabled", fault="")
    assert tile.find_element(By.CSS_SELECTOR, "svg.seven-segment").get_attribute("aria-label") == "display nSt"
    assert page.segments(tile) == ["", "ceg", "acdfg", "defg"]  # n S t, right-aligned
    assert page.led(tile, "RUN") == ("RUN blinking", "led-half-on", "0.4s")
    assert page.led(tile, "ERR") == ("ERR off", "none", "0s")
    assert page.led(page.tile(6), "OK") == ("OK on", "none", "0s")
    assert page.field(tile, "nmt") == "Pre-operational"

    # The master: NMT start, 6042h = 1500 rpm by SDO, then Shutdown, Switch on, Enable operation
    # on RPDO1 (6040h).
    bus.nmt(NMT_START, NODE)
    bus.sdo_write(NODE, 0x6042, 0, 1500, 2)
    bus.send(f"{0x200 + NODE:03X}#0600")
    page.wait_tile(tile, display="rdY", cia402="Ready to switch on")
    assert page.led(tile, "RUN") == ("RUN on", "none", "0s")
    bus.send(f"{0x200 + NODE:03X}#0700")
    bus.send(f"{0x200 + NODE:03X}#0F00")
    page.wait_tile(tile, cia402="Operation enabled")
    page.wait(lambda _: re.fullmatch(r"\d+\.\d", tile.get_attribute("data-display")), what="a frequency shown")
    page.wait_tile(tile, RAMP_TIMEOUT, display=RPM_1500_DISPLAY)
    assert page.segments(tile) == ["", "acdfg", "abcdef.", "abcdef"]  # 5 0. 0
    assert page.field(tile, "speed") == "1500 rpm"
    assert page.field(tile, "reference") == "1500 rpm"
    assert_trend_rises(page, NODE, 1500)
    # The state changes marked (Switched on may fall between two samples, the others may not).
    markers = [m["label"] for m in page.trend(NODE)["markers"] if m["label"] != "Switched on"]
    assert markers in (["NMT Operational", "Ready to switch on", "Operation enabled"],
                       ["Ready to switch on", "NMT Operational", "Operation enabled"]), markers
    page.screenshot("web-bench.png")

    # A fault by a click on the drive's page: the communication-loss fault COF, once the page has
    # the token it asks for.
    page.open_drive(NODE)
    assert browser.find_element(By.ID, "drive-title").text == "Node 4 · ATV312"
    assert browser.find_element(By.ID, "control-fields").get_property("disabled") is False
    page.give_token(TOKEN)
    mark = dump.mark()
    page.click_fault("COF")
    dump.expect(0x80 + NODE, "3081010000000000", timeout=PAGE_TIMEOUT, since=mark)
    assert page.reply() == "ok node 4: COF (CANopen communication fault (life guarding, heartbeat)), EMCY 8130"
    assert browser.find_element(By.ID, "command").text == "fault 4 COF"
    drive_tile = page.drive_tile()
    page.wait_tile(drive_tile, display="COF", fault="COF", cia402="Fault")
    assert page.segments(drive_tile) == ["", "adef", "abcdef", "aefg"]  # C O F
    page.wait_tile(tile, display="COF", fault="COF", cia402="Fault")  # the bench's tile, behind
    assert page.led(drive_tile, "ERR") == ("ERR double flash", "led-double-flash", "1.6s")
    assert page.field(drive_tile, "fault").startswith("COF (")
    page.wait(lambda _: any(m["label"] == "Fault" for m in page.trend(NODE)["markers"]), what="a Fault marker")
    page.screenshot("web-drive.png")
    assert page.console_errors() == []


def test_devicenet_drive_polled_by_a_scanner_and_a_fault_by_click(dump, start_dn, browser):
    daemon, _ = start_dn([MAC_ID], "--http", "0", "--http-actions")
    page = Page(browser, http_port(daemon))
    page.load()
    assert page.console_errors() == []
    tile = page.tile(MAC_ID)
    assert tile.find_element(By.CSS_SELECTOR, ".tile-title").text == "MAC ID 25 · ATV312"
    page.wait_tile(tile, display="nSt", fault="")
    assert page.led(tile, "MS") == ("MS green", "none", "0s")
    assert page.led(tile, "NS") == ("NS flashing green", "led-half-on", "1s")
    assert page.field(tile, "connection") == "online, no connection"

    poller = Poller(MAC_ID, "--timeout", POLL_ANSWER_MS, "--assembly", "21/71", "--set", "NetCtrl=1", "--set",
                    "NetRef=1", "--set", "Run_fwd=1", "--set", "Speed_reference=1200", "--every", POLL_MS)
    try:
        page.wait_tile(tile, RAMP_TIMEOUT, display=RPM_1200_DISPLAY, cia402="Operation enabled")
        assert page.led(tile, "NS") == ("NS green", "none", "0s")
        assert page.field(tile, "supervisor") == "enabled"
        assert_trend_rises(page, MAC_ID, 1200)

        page.open_drive(MAC_ID)
        mark = dump.mark()
        page.click_fault("OHF")
        # The poll response (group 1 message 0xF, 3C0h + MAC ID) with Faulted: Faulted, Ctrl from
        # net, Ref from net, At reference; Drive state 7 (Faulted); Speed actual 0.
        dump.expect(0x3C0 + MAC_ID, "E1070000", timeout=PAGE_TIMEOUT, since=mark)
        assert page.reply() == ("ok node 25: OHF (drive overheating), supervisor faulted, "
                                "Identity major recoverable fault")
        drive_tile = page.drive_tile()
        page.wait_tile(drive_tile, display="OHF", fault="OHF", cia402="Fault")
        assert page.field(drive_tile, "supervisor") == "faulted"
        # A fault of the drive is no fault of its card: MS stays green.
        assert page.led(drive_tile, "MS") == ("MS green", "none", "0s")
        poller.expect("Faulted=1", timeout=PAGE_TIMEOUT)
    finally:
        status = poller.stop()
        assert status == 0, f"dnscan poll exited {status}; its last lines: {drain(poller.lines)[-10:]}"
    assert page.console_errors() == []


def test_read_only_without_actions(bus, start_daemon, browser):
    daemon = start_daemon(bus, "--node-id", NODE, "--http", "0")
    page = Page(browser, http_port(daemon))
    page.load()
    page.open_drive(NODE)
    # The controls are there to see, disabled, with the reason; no token is asked for.
    assert browser.find_element(By.ID, "control-fields").get_property("disabled") is True
    assert all(not b.is_enabled() for b in browser.find_elements(By.CSS_SELECTOR, "#control-fields button"))
    assert browser.find_element(By.ID, "actions-off").text == (
        "Actions are off: start atv312d with --http-actions to use these controls.")
    assert not browser.find_element(By.ID, "token-form").is_displayed()
    assert page.console_errors() == []
