"""The live tuning page in Debian's headless chromium against
`tnvctl --emu serve --port 0`: it loads, the scope moves at >= 50 updates
per second, a parameter set round-trips, a refusal is shown with its
reason, the fault banner clears, the Bode view draws a result file and
measures the open loop on the node, two browsers obey the control rules,
the page needs the secret of its URL (a page of another origin cannot
command), and closing the tab that has control stops its jog."""

import json
import os
import time

import pytest
from conftest import wait_for
from page_http import owner, position_samples

HERE = os.path.dirname(os.path.abspath(__file__))
PARAM = "motion.move_ramp_s"  # 0.001 .. 10 s, applied live, not a safety parameter


def page_value(browser, expr):
    return browser.execute_script(f"return {expr};")


def open_page(browser, url):
    browser.get(url)
    wait_for(lambda: page_value(browser, "window.tnvPage && window.tnvPage.events > 0"), 30,
             "the first telemetry event on the page")
    wait_for(lambda: browser.find_elements("css selector", f'tr[data-param="{PARAM}"]'), 15,
             "the parameter table")


def take_control(browser):
    browser.find_element("id", "take-control").click()
    wait_for(lambda: page_value(browser, "window.tnvPage.control.you"), 5, "control taken")


def row(browser, name):
    return browser.find_element("css selector", f'tr[data-param="{name}"]')


def row_state(browser, name):
    """What a parameter row shows: {value, msg, refusal}, read in one round trip."""
    return browser.execute_script("""const tr = document.querySelector(`tr[data-param="${arguments[0]}"]`);
        if (!tr) return null;
        const msg = tr.querySelector('td.msg');
        return {value: tr.querySelector('td.value').textContent, msg: msg.textContent,
                refusal: msg.classList.contains('refusal')};""", name)


def set_value(browser, name, text):
    r = row(browser, name)
    box = r.find_element("css selector", "input")
    box.clear()
    box.send_keys(text)
    r.find_element("css selector", "button.set").click()


@pytest.fixture(scope="module")
def first(server, browsers):
    b = browsers()
    open_page(b, server)
    take_control(b)
    return b


def test_the_scope_moves_at_50_updates_per_second(first, screenshot):
    first.find_element("css selector", '[data-motion="circle"]').click()
    newest = "Chart.getChart('scope').data.datasets[0].data.slice(-1)[0].x"
    newest_before = page_value(first, newest)
    t_before = page_value(first, "window.tnvPage.lastT")
    updates_before = page_value(first, "window.tnvPage.updates")
    started = time.monotonic()
    time.sleep(2.0)
    updates = page_value(first, "window.tnvPage.updates") - updates_before
    elapsed = time.monotonic() - started
    rate = page_value(first, "window.tnvPage.updatesPerS")
    assert page_value(first, "window.tnvPage.lastT") > t_before + 1.5, "the scope's time did not advance"
    assert page_value(first, newest) > newest_before + 1.5, "the trace's newest point did not advance"
    assert page_value(first, "window.tnvPage.points()") >= 3 * 900, "less than 10 s of three traces drawn"
    assert updates / elapsed >= 50.0, f"{updates} scope updates in {elapsed:.2f} s"
    assert rate >= 50.0, f"the page's counter shows {rate} updates/s"
    print(f"scope: {updates / elapsed:.1f} updates/s measured, page counter {rate:.0f}/s")
    # The circle moves x: its trace spans more than 0.5 mm in the window.
    span = page_value(first, """(() => { const d = Chart.getChart('scope').data.datasets
        .find((s) => s.label === 'pos_x_mm').data.map((p) => p.y).filter((y) => y !== null);
        return Math.max(...d) - Math.min(...d); })()""")
    assert span > 0.5, f"pos_x_mm spans {span} mm during a circle"
    first.find_element("id", "pause").click()
    frozen = page_value(first, "window.tnvPage.updates")
    time.sleep(0.3)
    assert page_value(first, "window.tnvPage.updates") == frozen, "the scope kept drawing while paused"
    box = first.find_element("id", "scope")
    for dx in (-300, 200):  # cursor A, then cursor B
        first.execute_script("""const c = Chart.getChart('scope'); const r = arguments[0].getBoundingClientRect();
            arguments[0].dispatchEvent(new MouseEvent('click', {clientX: r.left + r.width / 2 + arguments[1],
            clientY: r.top + r.height / 2, bubbles: true}));""", box, dx)
    readout = first.find_element("id", "cursor-readout").text
    assert "Δt" in readout and "pos_x_mm" in readout, readout
    screenshot(first, "tuning-scope")
    # Left paused: the later tests need no redraws (the data keeps arriving).


def test_a_parameter_set_round_trips_and_a_refusal_is_shown(first, screenshot):
    first.find_element("id", "param-filter").send_keys("motion.")
    set_value(first, PARAM, "0.25")
    wait_for(lambda: row_state(first, PARAM)["msg"] == "read back 0.25", 10, "the value read back after the set")
    assert row_state(first, PARAM)["value"] == "0.25"
    set_value(first, PARAM, "50")
    state = wait_for(lambda: (lambda s: s if s["refusal"] else None)(row_state(first, PARAM)), 10, "the refusal")
    assert PARAM in state["msg"] and "10" in state["msg"], f"the refusal does not name the range: {state['msg']!r}"
    assert state["value"] == "0.25", "a refused value was shown"
    # The node still has 0.25: the table read again shows it.
    first.find_element("id", "param-refresh").click()
    wait_for(lambda: row_state(first, PARAM)["msg"] == "", 10, "the table read again")
    assert row_state(first, PARAM)["value"] == "0.25"
    set_value(first, PARAM, "50")
    wait_for(lambda: row_state(first, PARAM)["refusal"], 10, "the refusal again")
    first.execute_script("arguments[0].scrollIntoView({block: 'center'});", row(first, PARAM))
    screenshot(first, "tuning-refusal")


def test_the_fault_banner_shows_the_reason_and_clears(first):
    first.find_element("css selector", '[data-motion="estop"]').click()
    wait_for(lambda: first.find_element("id", "fault-banner").is_displayed(), 10, "the fault banner")
    assert "estop" in first.find_element("id", "fault-reason").text
    first.find_element("id", "clear-fault").click()
    wait_for(lambda: not first.find_element("id", "fault-banner").is_displayed(), 10, "the banner gone after clear")


def test_a_capture_is_drawn_and_downloads_as_csv(first):
    duration = first.find_element("id", "capture-duration")
    duration.clear()
    duration.send_keys("0.5")
    first.find_element("id", "capture-channels").send_keys("pos_x,pos_y")
    first.find_element("id", "capture-take").click()
    wait_for(lambda: first.find_elements("css selector", "#capture-list li"), 20, "the capture in the list")
    wait_for(lambda: page_value(first, "(Chart.getChart('capture-chart') || {data: {datasets: []}}).data.datasets.length")
             == 2, 10, "the capture drawn (pos_x_mm, pos_y_mm)")
    csv = first.execute_script("""const a = document.querySelector('#capture-list li a');
        return fetch(a.href).then((r) => r.text());""")
    assert csv.startswith("t_s,pos_x_mm,pos_y_mm\n"), csv[:80]
    assert 450 <= len(csv.strip().splitlines()) - 1 <= 550, "not about 500 samples of 1 ms in 0.5 s"


def test_the_bode_view_draws_a_result_file(first):
    first.find_element("id", "bode-file").send_keys(os.path.join(HERE, "bode_fixture.json"))
    wait_for(lambda: page_value(first, "window.tnvPage.bode && window.tnvPage.bode.points === 11"), 10,
             "11 Bode points drawn")
    margins = first.find_element("id", "margins").text
    assert "52.0" in margins and "22.0" in margins and "30.50" in margins, margins
    assert page_value(first, "Chart.getChart('bode-gain').data.datasets.length") == 3  # gain, coherence, model


def test_the_bode_view_measures_the_open_loop_on_the_node(first, screenshot):
    first.find_element("css selector", '[data-motion="enable"]').click()
    time.sleep(0.5)
    first.find_element("id", "bode-loop").send_keys("open")
    first.find_element("id", "bode-measure").click()
    # Two experiments of 12 s of machine time on the emulated node.
    wait_for(lambda: page_value(first, "window.tnvPage.bode && window.tnvPage.bode.points > 11")
             or not first.find_element("id", "bode-error").text.startswith("measuring"), 240,
             "the measured open loop or an error")
    assert not first.find_element("id", "bode-error").text, first.find_element("id", "bode-error").text
    margins = first.find_element("id", "margins").text
    assert "crossover" in margins and "model:" in margins, margins
    first.execute_script("document.getElementById('bode-section').scrollIntoView();")
    screenshot(first, "tuning-bode")


def test_a_second_browser_reads_only_and_is_told_why(first, server, browsers):
    # Both scopes paused (the data keeps arriving): two pages redrawing at
    # 100 Hz would only slow a busy test machine down.
    second = browsers()
    open_page(second, server)
    second.find_element("id", "pause").click()
    wait_for(lambda: "another browser has control" in second.find_element("id", "control-state").text, 10,
             "the second browser's read-only state")
    before = row_state(first, PARAM)["value"]
    second.find_element("id", "take-control").click()
    wait_for(lambda: second.find_element("id", "control-error").text == "another browser has control", 10,
             "the refusal to take control")
    set_value(second, PARAM, "0.5")
    wait_for(lambda: row_state(second, PARAM)["msg"] == "another browser has control", 10,
             "the refusal of a set from the second browser")
    assert row_state(second, PARAM)["value"] == before
    assert row_state(first, PARAM)["value"] == before, "the read-only browser's set changed the value"
    # Both see the same node: the second browser's scope moves too.
    t0 = page_value(second, "window.tnvPage.lastT")
    time.sleep(0.5)
    assert page_value(second, "window.tnvPage.lastT") > t0
    # Released by the first, taken by the second; now the first is refused.
    first.find_element("id", "release-control").click()
    take_control(second)
    wait_for(lambda: "another browser has control" in first.find_element("id", "control-state").text, 10,
             "the first browser's read-only state")


def audit_lines(server):
    return [json.loads(line) for line in server.audit.read_text().splitlines()]


def test_the_page_needs_its_secret_and_another_origin_cannot_command(server, browsers):
    port = server.host.rsplit(":", 1)[1]
    b = browsers()
    # Without the URL's secret the page loads but the API refuses it, and says how to get in.
    b.get(f"http://localhost:{port}/")
    wait_for(lambda: "no valid session" in b.find_element("id", "node-info").text, 15,
             "the page's refusal without the secret")
    # With it, the secret is gone from the address bar, held as a cookie the scripts cannot read.
    b.get(server)
    wait_for(lambda: page_value(b, "window.tnvPage && window.tnvPage.events > 0"), 30, "telemetry with the secret")
    assert "token=" not in b.current_url, b.current_url
    assert "tnv_session" not in page_value(b, "document.cookie"), "the session cookie is readable by scripts"
    # A page of another origin (localhost is another site than 127.0.0.1) in
    # the same browser posts a command with credentials: refused, nothing changed.
    before = owner(server, "/api/status")["heartbeat"]["state"]
    b.get(f"http://localhost:{port}/")
    n = len(audit_lines(server))
    b.execute_script("""return fetch(arguments[0] + '/api/motion', {method: 'POST', mode: 'no-cors',
        credentials: 'include', headers: {'Content-Type': 'text/plain'}, body: '{"kind":"enable"}'})
        .then(() => true, () => false);""", server.base)
    posted = wait_for(lambda: [l for l in audit_lines(server)[n:] if l.get("path") == "/api/motion"], 10,
                      "the cross-origin post in the audit trail")
    assert posted[0]["status"] in (401, 403), posted[0]
    assert owner(server, "/api/status")["heartbeat"]["state"] == before
    print(f"cross-origin post: answered {posted[0]['status']} ({posted[0]['answer']['error']})")


def test_closing_the_tab_with_control_stops_its_jog(server, browsers):
    holder = next((b for b in browsers.opened if page_value(b, "window.tnvPage && window.tnvPage.control.you")), None)
    if holder is None:
        holder = browsers()
        open_page(holder, server)
        take_control(holder)
    # The stop ramps down over motion.move_ramp_s: back to its default 20 ms (an earlier test set 0.25 s).
    set_value(holder, PARAM, "0.02")
    wait_for(lambda: row_state(holder, PARAM)["msg"] == "read back 0.02", 10, "the ramp back at 0.02 s")
    holder.find_element("css selector", '[data-motion="enable"]').click()
    wait_for(lambda: owner(server, "/api/status")["heartbeat"]["state"] != "idle", 10, "servo on")
    speed = holder.find_element("id", "move-speed")
    speed.clear()
    speed.send_keys("1")  # X +5 mm at 1 mm/s: a 5 s jog
    holder.find_element("css selector", '[data-motion="move"][data-axis="x"][data-distance="5"]').click()
    wait_for(lambda: owner(server, "/api/status")["heartbeat"]["state"] == "moving", 10, "the jog running")
    time.sleep(0.3)
    t_close = page_value(holder, "window.tnvPage.lastT")  # the newest sample the page saw: before the close
    browsers.opened.remove(holder)
    holder.quit()
    after = [(t, x) for t, x in position_samples(server, lambda t: t > t_close + 2.0) if t > t_close]
    assert after and after[-1][0] > t_close + 2.0, "the stream ended before 2 s of machine time after the close"
    # At rest: within 10 um of where the table ended (an encoder count is 0.4 um; the servo holds).
    t_moved = max([t for t, x in after if abs(x - after[-1][1]) > 0.01], default=t_close)
    stopped_after = t_moved - t_close
    print(f"dead-man: the jog stopped {stopped_after:.3f} s of machine time after the tab closed")
    # From before quit() to rest: the browser's own shutdown (hundreds of ms on a loaded machine) is in
    # it. The 0.5 s goal is DeadmanTest's (test_serve); here a generous bound, well under the module's
    # 3 s dead-man time, so a pass is the closed stream's doing.
    assert stopped_after <= 1.5, f"the jog ran {stopped_after:.3f} s of machine time after the tab closed"
    assert owner(server, "/api/control")["taken"] is False, "the closed tab kept control"
    events = [l for l in audit_lines(server) if l.get("event") == "dead-man"]
    assert events and "motion stopped" in events[-1]["detail"], events
