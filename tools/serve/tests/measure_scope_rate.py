"""The scope's redraw rate, a measurement for the docs, not a test: how
many times a second the page redraws while a circle runs depends on the
machine and its load, so no CI stage compares it with a constant.

    TNVCTL_EXE=build/release/tools/tnvctl/tnvctl \\
        python3 -m pytest -q -s -p no:cacheprovider tools/serve/tests/measure_scope_rate.py

prints the redraws per second counted over 5 s of wall time, the page's own
counter and the telemetry events per second (docs/tuning-guide.md reports
the figure). pytest collects this file only when it is named."""

import time

from test_tuning_page import open_page, page_value, take_control

WALL_S = 5.0


def test_measure_scope_rate(server, browsers):
    browser = browsers()
    open_page(browser, server)
    take_control(browser)
    browser.find_element("css selector", '[data-motion="circle"]').click()
    time.sleep(1.0)  # past the first batch, which carries the whole history
    updates0, events0 = page_value(browser, "window.tnvPage.updates"), page_value(browser, "window.tnvPage.events")
    started = time.monotonic()
    time.sleep(WALL_S)
    elapsed = time.monotonic() - started
    updates = page_value(browser, "window.tnvPage.updates") - updates0
    events = page_value(browser, "window.tnvPage.events") - events0
    counter = page_value(browser, "window.tnvPage.updatesPerS")
    print(f"\nscope: {updates / elapsed:.1f} redraws/s, {events / elapsed:.1f} telemetry events/s "
          f"over {elapsed:.2f} s; the page's counter shows {counter:.0f}/s")
    assert updates > 0, "the scope never redrew while a circle ran"
