"""The Program panel in Debian's headless chromium against
`tnvctl --emu serve --port 0`: a refused program is shown with its line
and column, a program loaded from a file is previewed (its path drawn, one
polyline per segment), and run from the tab with control to its end on the
emulated node, the current line advancing through the program and the tool
marker following the table; a pause and its Resume; a run from line (a
line outside the program refused and nothing started, then a run from
line 4 that shows no line before it); the feed hold and its release."""

import pytest
from conftest import wait_for
from program_panel import open_program_tab, program_state
from test_tuning_page import page_value

# Incremental: it runs from wherever the table stands. Lines 3 and 4 are lines,
# line 5 a half circle back to the start; 21 mm at 10 mm/s, each line 0.5 s or more.
PROGRAM = """(the page's test piece)
G21 G91 G17
G1 X5 Y0 F600
G1 X0 Y5
G2 X-5 Y-5 I-2.5 J-2.5
M2
"""
REFUSED = "G21 G90\nG1 X5 F100\nG1 X20 E3\n"  # line 3, column 8: unsupported word E


@pytest.fixture(scope="module")
def tab(server, browsers):
    return open_program_tab(server, browsers)


def test_a_refused_program_is_shown_with_its_line_and_column(tab):
    box = tab.find_element("id", "program-text")
    box.clear()
    box.send_keys(REFUSED)
    tab.find_element("id", "program-preview").click()
    text = wait_for(lambda: (lambda t: t if "line 3" in t else None)(tab.find_element("id", "program-error").text), 60,
                    "the refusal naming line 3")
    assert "column 8" in text, text
    assert page_value(tab, "document.querySelectorAll('#program-path polyline').length") == 0


def test_a_loaded_program_is_previewed_and_runs_to_its_end(tab, tmp_path, screenshot):
    path = tmp_path / "piece.ngc"
    path.write_text(PROGRAM)
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == 3, 60, "the preview's three pieces drawn")
    preview = program_state(tab)["preview"]
    assert [p["line"] for p in preview["pieces"]] == [3, 4, 5]
    assert preview["segments"] == 3
    assert len(preview["pieces"][2]["points"]) == 2 * 37, "the half circle is not drawn in 5-degree chords"
    lines = page_value(tab, "Array.from(document.querySelectorAll('#program-path polyline')).map((e) => e.dataset.line)")
    assert lines == ["3", "4", "5"], lines
    assert "programmed cycle time" in tab.find_element("id", "program-info").text
    start = preview["start"]

    tab.find_element("id", "program-run").click()
    state = wait_for(lambda: (lambda s: s if s["phase"] == "ended" else None)(program_state(tab)), 120,
                     "the run's end")
    assert state["end"] == "done", (state, tab.find_element("id", "program-state").text,
                                     tab.find_element("id", "program-error").text)
    seen = state["linesSeen"]
    print(f"current lines shown during the run: {seen}")
    assert len(seen) >= 2 and seen == sorted(seen) and seen[-1] == 5, f"the current line did not advance to 5: {seen}"
    assert "done" in tab.find_element("id", "program-state").text
    # The tool marker follows the telemetry: back at the start after the half circle (an encoder count is 0.4 um).
    wait_for(lambda: (lambda t: t and abs(t[0] - start[0]) < 0.01 and abs(t[1] - start[1]) < 0.01)(
        program_state(tab)["tool"]), 60, "the tool back at the start")
    marker = page_value(tab, "[Number(document.querySelector('#program-path .tool').getAttribute('cx')),"
                             " Number(document.querySelector('#program-path .tool').getAttribute('cy'))]")
    assert abs(marker[0] - start[0]) < 0.01 and abs(marker[1] - start[1]) < 0.01, marker
    screenshot(tab, "tuning-program")


PAUSING = """(a program stop between two lines)
G21 G91 G17
G1 X2 Y0 F600
M0
G1 X-2 Y0
M2
"""


def test_a_paused_program_shows_resume_and_continues_on_it(tab, tmp_path):
    path = tmp_path / "pausing.ngc"
    path.write_text(PAUSING)
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == 2, 60, "the preview's two pieces drawn")
    assert not tab.find_element("id", "program-resume").is_displayed(), "Resume shown with nothing paused"
    tab.find_element("id", "program-run").click()
    wait_for(lambda: (lambda p: p if p else None)(program_state(tab)["pause"]), 60, "the pause at line 4")
    pause = program_state(tab)["pause"]
    assert pause["line"] == 4 and pause["reason"] == "program stop (M0)", pause
    assert "paused at line 4" in tab.find_element("id", "program-state").text
    wait_for(lambda: tab.find_element("id", "program-resume").is_displayed(), 10, "the Resume button")
    tab.find_element("id", "program-resume").click()
    state = wait_for(lambda: (lambda s: s if s["phase"] == "ended" else None)(program_state(tab)), 60, "the run's end")
    assert state["end"] == "done", (state, tab.find_element("id", "program-state").text)
    assert not tab.find_element("id", "program-resume").is_displayed()


def test_a_run_from_line_runs_from_there_and_a_bad_line_starts_nothing(tab, tmp_path):
    path = tmp_path / "from-line.ngc"
    path.write_text(PROGRAM)
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == 3, 60, "the preview's three pieces drawn")
    before = program_state(tab)["run"]
    from_line = tab.find_element("id", "program-from-line")
    try:
        from_line.send_keys("99")
        tab.find_element("id", "program-run").click()
        text = wait_for(lambda: (lambda t: t if "cannot run from line 99" in t else None)(
            tab.find_element("id", "program-error").text), 60, "the refusal of line 99")
        assert "lines 1 to" in text, text
        assert program_state(tab)["run"] == before, "a refused start began a run"

        from_line.clear()
        from_line.send_keys("4")
        tab.find_element("id", "program-run").click()
        state = wait_for(lambda: (lambda s: s if s["phase"] == "ended" and s["run"] > before else None)(
            program_state(tab)), 120, "the end of the run from line 4")
        assert state["end"] == "done", (state, tab.find_element("id", "program-error").text)
        seen = state["linesSeen"]
        print(f"current lines shown during the run from line 4: {seen}")
        assert seen and min(seen) >= 4 and seen[-1] == 5, f"a line before 4 ran, or 5 was not reached: {seen}"
        assert [p["line"] for p in program_state(tab)["preview"]["pieces"]][-1] == 5
    finally:
        from_line.clear()


def test_feed_hold_holds_on_the_path_and_feed_resume_goes_on(tab, tmp_path):
    path = tmp_path / "long.ngc"
    path.write_text("G21 G91 G17 F300\n" + "G1 X0.5\n" * 60 + "G1 X-30\n")  # 60 s of machine time: never ends here
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == 61, 60, "the preview's 61 pieces drawn")
    tab.find_element("id", "program-run").click()
    wait_for(lambda: (lambda s: s["phase"] == "running" and s["line"] >= 3)(program_state(tab)), 60, "the run under way")
    hold = tab.find_element("id", "program-hold")
    hold.click()
    wait_for(lambda: "feed held at line" in tab.find_element("id", "program-state").text, 60, "the feed held")
    assert hold.text == "Feed resume", hold.text
    held_line = program_state(tab)["line"]
    hold.click()
    wait_for(lambda: program_state(tab)["line"] >= held_line + 2, 60, "the program going on past the held line")
    tab.find_element("id", "program-stop").click()
    state = wait_for(lambda: (lambda s: s if s["phase"] == "ended" else None)(program_state(tab)), 60, "the stop")
    assert state["end"] == "interrupted", state
