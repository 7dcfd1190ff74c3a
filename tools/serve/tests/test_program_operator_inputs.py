"""The Program panel's operator inputs in Debian's headless chromium against
`tnvctl --emu serve --port 0`, judged by what the node reports back
(PROGRAM_STATUS: its state, the element it runs and so the line, its pauses;
PROGRAM_TOOL: the tool in the spindle) and by the elements sent to it:
the optional stop switch (M1 pauses the node, or is not sent), the block
delete switch (the slashed line skipped, or run by the node), the tool
table (M6 refused without it; with it the node pauses and then knows tool
2), the feed hold (the node holds, then runs on) and a run from line (the
node starts at that line). No assertion counts wall time: each waits for
what the node reports, with a generous limit."""

import pytest
from conftest import wait_for
from program_panel import open_program_tab, program_state
from test_tuning_page import page_value


@pytest.fixture(scope="module")
def tab(server, browsers):
    return open_program_tab(server, browsers)


def load(tab, tmp_path, name, text, pieces):
    path = tmp_path / name
    path.write_text(text)
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == pieces and
             page_value(tab, "document.getElementById('program-text').value").startswith(text[:20]), 60,
             f"the preview of {name}")


def run_to_end(tab, resume_pauses=False):
    before = program_state(tab)["run"]
    tab.find_element("id", "program-run").click()

    def ended():
        from selenium.common.exceptions import ElementClickInterceptedException, ElementNotInteractableException

        s = program_state(tab)
        if resume_pauses and s["pause"] and tab.find_element("id", "program-resume").is_displayed():
            try:
                tab.find_element("id", "program-resume").click()
            except (ElementNotInteractableException, ElementClickInterceptedException):
                pass  # the panel redrew between the look and the click: the next look clicks again
        return s if s["phase"] == "ended" and s["run"] > before else None

    state = wait_for(ended, 120, "the run's end")
    assert state["end"] == "done", (state, tab.find_element("id", "program-state").text,
                                     tab.find_element("id", "program-error").text)
    return state


def set_checkbox(tab, name, on):
    box = tab.find_element("id", name)
    if box.is_selected() != on:
        box.click()
    assert box.is_selected() == on


OPTIONAL_STOP = "G21 G91 G17\nG1 X2 F600\nM1\nG1 X-2\nM2\n"


def test_the_optional_stop_switch_decides_whether_the_node_pauses_at_m1(tab, tmp_path):
    load(tab, tmp_path, "m1.ngc", OPTIONAL_STOP, 2)
    try:
        set_checkbox(tab, "program-optional-stop", True)
        on = run_to_end(tab, resume_pauses=True)
        assert on["pausesSeen"] == [{"line": 3, "reason": "optional stop (M1)"}], on["pausesSeen"]
        assert "paused" in on["nodeStatesSeen"], on["nodeStatesSeen"]
        set_checkbox(tab, "program-optional-stop", False)
        off = run_to_end(tab)
        assert off["pausesSeen"] == [] and "paused" not in off["nodeStatesSeen"], off
        assert off["total"] == on["total"] - 1, ("the M1 pause is not sent with the switch off", on["total"],
                                                  off["total"])
    finally:
        set_checkbox(tab, "program-optional-stop", True)


BLOCK_DELETE = "G21 G91 G17 F600\nG1 X2\n/G1 Y2\nG1 X-2\nM2\n"


def test_the_block_delete_switch_decides_whether_the_node_runs_the_slashed_line(tab, tmp_path):
    load(tab, tmp_path, "slash.ngc", BLOCK_DELETE, 2)
    try:
        set_checkbox(tab, "program-block-delete", True)
        on = run_to_end(tab)
        assert 3 not in on["linesSeen"], on["linesSeen"]
        set_checkbox(tab, "program-block-delete", False)
        off = run_to_end(tab)
        assert 3 in off["linesSeen"], ("the node never ran line 3", off["linesSeen"])
        assert off["total"] == on["total"] + 1, (on["total"], off["total"])
    finally:
        set_checkbox(tab, "program-block-delete", True)


TOOL_CHANGE = "G21 G91 G17\nT2 M6\nG1 X2 F600\nG1 X-2\nM2\n"


def test_the_tool_table_makes_m6_run_and_the_node_knows_the_tool_once_confirmed(tab, tmp_path):
    path = tmp_path / "t2.ngc"
    path.write_text(TOOL_CHANGE)
    tab.find_element("id", "program-file").send_keys(str(path))
    wait_for(lambda: "requested tool 2 not found" in tab.find_element("id", "program-error").text, 60,
             "the refusal of T2 without a tool table")
    before = program_state(tab)["run"]
    tab.find_element("id", "program-run").click()
    wait_for(lambda: "requested tool 2 not found" in tab.find_element("id", "program-error").text, 60,
             "Run refused likewise")
    assert program_state(tab)["run"] == before, "a refused run began"

    table = tmp_path / "tools.tbl"
    table.write_text("T2 P2 Z30 D6\n")
    tab.find_element("id", "program-tool-table").send_keys(str(table))
    wait_for(lambda: page_value(tab, "window.tnvPage.program.drawn") == 2, 60, "the preview with the table")
    state = run_to_end(tab, resume_pauses=True)
    assert state["pausesSeen"] == [{"line": 2, "reason": "tool change (M6)"}], state["pausesSeen"]
    tool = wait_for(lambda: program_state(tab)["spindleTool"], 60, "the node's PROGRAM_TOOL")
    assert tool["known"] and tool["tool"] == 2, tool


def test_feed_hold_is_the_nodes_holding_and_resume_runs_on(tab, tmp_path):
    load(tab, tmp_path, "long-hold.ngc", "G21 G91 G17 F300\n" + "G1 X0.5\n" * 60 + "G1 X-30\n", 61)
    tab.find_element("id", "program-run").click()
    wait_for(lambda: (lambda s: s["phase"] == "running" and s["line"] >= 3)(program_state(tab)), 60, "the run under way")
    hold = tab.find_element("id", "program-hold")
    hold.click()
    wait_for(lambda: "holding" in program_state(tab)["nodeStatesSeen"], 60, "the node holding")
    held_line = program_state(tab)["line"]
    hold.click()
    wait_for(lambda: program_state(tab)["nodeStatesSeen"][-1] == "running" and
             program_state(tab)["line"] >= held_line + 2, 60, "the node running on past the held line")
    seen = program_state(tab)["nodeStatesSeen"]
    assert seen.index("holding") < len(seen) - 1, seen
    tab.find_element("id", "program-stop").click()
    state = wait_for(lambda: (lambda s: s if s["phase"] == "ended" else None)(program_state(tab)), 60, "the stop")
    assert state["end"] == "interrupted", state


def test_a_run_from_line_starts_the_node_at_that_line(tab, tmp_path):
    load(tab, tmp_path, "from.ngc", "G21 G91 G17\nG1 X2 F600\nG1 Y2\nG1 X-2\nG1 Y-2\nM2\n", 4)
    whole = run_to_end(tab)
    from_line = tab.find_element("id", "program-from-line")
    try:
        from_line.send_keys("4")
        # The node knows tool 2 from the tool change test before: line 4 runs without a tool (T0), so the start
        # may change to it first (a pause, resumed here).
        part = run_to_end(tab, resume_pauses=True)
    finally:
        from_line.clear()
    print(f"run from line 4: lines {part['linesSeen']}, pauses {part['pausesSeen']}, node {part['nodeStatesSeen']}")
    assert min(part["linesSeen"]) >= 4 and part["linesSeen"][-1] == 5, part["linesSeen"]
    assert 2 in whole["linesSeen"] and 3 in whole["linesSeen"], whole["linesSeen"]
