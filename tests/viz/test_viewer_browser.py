"""The viewer in a real headless browser: Debian's Chromium driven by Selenium (no browser download).

The page loads without console errors, the time and throw sliders move the frame, play advances it, and a
screenshot shows the part (pixels of its fill colour). The screenshot is kept in the test's tmp dir and, when
``THROWMAP_SCREENSHOT_DIR`` is set, there too. Without Chromium, chromedriver or Selenium the test says so and
skips (``make test`` installs Chromium where it can: Debian, as root).
"""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import numpy as np
import pytest

from throwmap.viz.viewer import PART_COLORS, player_data, viewer_html, write_viewer

CHROMIUM = ("/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome")
DRIVER = "/usr/bin/chromedriver"
FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-dev-shm-usage", "--window-size=1300,1000")
"""The networking flags keep Chromium from calling out (refused on a closed network: console noise)."""


def _browser_or_skip():
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is not installed (pip install selenium)")
    binary = next((b for b in CHROMIUM if os.path.exists(b)), shutil.which("chromium"))
    driver = DRIVER if os.path.exists(DRIVER) else shutil.which("chromedriver")
    if not binary or not driver:
        pytest.skip("no Chromium/chromedriver on this machine (apt-get install chromium chromium-driver; "
                    "`make test` does it as root on Debian)")
    return webdriver, binary, driver


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    webdriver, binary, driver = _browser_or_skip()
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = binary
    for flag in FLAGS:
        opts.add_argument(flag)
    opts.add_argument(f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}")
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    try:
        drv = webdriver.Chrome(service=Service(driver), options=opts)
    except Exception as err:  # noqa: BLE001 - a browser that does not start is a skip, with its reason
        pytest.skip(f"Chromium did not start: {type(err).__name__}: {str(err).splitlines()[0] if str(err) else ''}")
    drv.set_page_load_timeout(30)
    yield drv
    drv.quit()


def _colour_pixels(png: bytes, hexcolour: str, tol: int = 6) -> int:
    from io import BytesIO

    from PIL import Image

    img = np.asarray(Image.open(BytesIO(png)).convert("RGB")).astype(int)
    rgb = np.array([int(hexcolour[i:i + 2], 16) for i in (1, 3, 5)])
    return int(np.sum(np.all(np.abs(img - rgb) <= tol, axis=2)))


def _set_range(driver, element_id: str, value: int) -> None:
    driver.execute_script(
        "const e = document.getElementById(arguments[0]); e.value = String(arguments[1]);"
        "e.dispatchEvent(new Event('input', {bubbles: true}));", element_id, value)


def _errors(driver) -> list:
    return [e for e in driver.get_log("browser") if e.get("level") in ("SEVERE", "ERROR")]


def test_the_page_plays_in_chromium(browser, tmp_path, two_part_trajectory):
    out = write_viewer(tmp_path / "view.html", viewer_html(title="browser test", subtitle="two parts",
                                                           player=player_data(two_part_trajectory)))
    browser.get(out.resolve().as_uri())
    player = browser.find_element("id", "player")
    assert _errors(browser) == []
    assert browser.execute_script("return performance.getEntriesByType('resource').length;") == 0  # nothing fetched
    assert player.get_attribute("data-frame") == "0"
    n = int(browser.find_element("id", "frame").get_attribute("max")) + 1
    assert n > 10
    first = browser.execute_script("return document.getElementById('scene').toDataURL();")

    _set_range(browser, "frame", n // 2)  # the time slider moves the frame
    assert player.get_attribute("data-frame") == str(n // 2)
    middle = browser.execute_script("return document.getElementById('scene').toDataURL();")
    assert middle != first  # the drawing changed

    _set_range(browser, "throw", 2)  # the throw slider: the start of the third playable step
    step = int(player.get_attribute("data-step"))
    assert step >= 0 and int(player.get_attribute("data-frame")) != n // 2

    browser.find_element("id", "next-throw").click()  # the start of the next step
    assert int(player.get_attribute("data-step")) == step + 1
    browser.find_element("id", "prev-throw").click()
    assert int(player.get_attribute("data-step")) == step
    browser.find_element("id", "step-fwd").click()
    frame = int(player.get_attribute("data-frame"))
    browser.find_element("id", "play").click()  # play advances by itself
    deadline = time.monotonic() + 5
    while int(player.get_attribute("data-frame")) == frame and time.monotonic() < deadline:
        time.sleep(0.05)
    assert int(player.get_attribute("data-frame")) > frame
    browser.find_element("id", "play").click()
    assert player.get_attribute("data-playing") == "false"

    _set_range(browser, "frame", n // 2)
    png = browser.get_screenshot_as_png()
    (tmp_path / "viewer.png").write_bytes(png)
    if os.environ.get("THROWMAP_SCREENSHOT_DIR"):
        keep = Path(os.environ["THROWMAP_SCREENSHOT_DIR"])
        keep.mkdir(parents=True, exist_ok=True)
        (keep / "viewer.png").write_bytes(png)
    for colour in PART_COLORS[:2]:  # both parts are drawn (scene and orbit plot)
        assert _colour_pixels(png, colour) > 200, colour
    assert _errors(browser) == []


def test_pages_without_an_orbit_or_a_player_load_cleanly(browser, tmp_path, two_part_trajectory):
    import dataclasses

    from throwmap.viz.viewer import table_html

    bare = dataclasses.replace(two_part_trajectory, meta={})
    for name, player, sections in (("bare", player_data(bare), ""),
                                   ("tables", None, table_html(("k", "v"), [("a", 1)], table_id="t"))):
        out = write_viewer(tmp_path / f"{name}.html", viewer_html(title=name, player=player, sections=sections))
        browser.get(out.resolve().as_uri())
        assert _errors(browser) == [], name
        player_el = browser.find_element("id", "player")
        if player is None:
            assert not player_el.is_displayed() and browser.find_element("id", "t").is_displayed()
        else:
            assert browser.find_element("id", "throw").get_attribute("disabled") is not None
            _set_range(browser, "frame", 5)
            assert player_el.get_attribute("data-frame") == "5" and player_el.get_attribute("data-step") == "-1"
            assert _errors(browser) == [], name
