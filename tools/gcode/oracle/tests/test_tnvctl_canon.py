"""`tnvctl gcode canon` as a command (no rs274 needed): output, refusals,
options."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
import canon_compare  # noqa: E402

pytestmark = pytest.mark.skipif(canon_compare.env_tnvctl() is None, reason="TNVCTL_EXE not set to the built tnvctl")


def run(*args: str, tnvctl_flags: tuple[str, ...] = ()) -> subprocess.CompletedProcess:
    return subprocess.run([canon_compare.env_tnvctl(), *tnvctl_flags, "gcode", "canon", *args], capture_output=True,
                          text=True, timeout=60, stdin=subprocess.DEVNULL)


def write(path: Path, text: str) -> str:
    path.write_text(text)
    return str(path)


def test_prints_one_call_a_line(tmp_path):
    p = run(write(tmp_path / "p.ngc", "G21\nT1 M6\nG43\nG0 X1 Z2\nM2\n"),
            "--tool-table", write(tmp_path / "t.tbl", "T1 P1 Z12.5 D6 ;end mill\n"))
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[0] == "USE_LENGTH_UNITS(CANON_UNITS_MM)"
    assert "USE_TOOL_LENGTH_OFFSET(0.0000 0.0000 12.5000, 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)" in lines
    assert "STRAIGHT_TRAVERSE(1.0000, 0.0000, 2.0000, 0.0000, 0.0000, 0.0000)" in lines  # program coordinates
    assert lines[-1] == "PROGRAM_END()"


def test_json_output(tmp_path):
    p = run(write(tmp_path / "p.ngc", "G0 X1\nM2\n"), tnvctl_flags=("--json",))
    assert p.returncode == 0, p.stderr
    calls = json.loads(p.stdout)["calls"]
    assert {"line": 1, "call": "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)"} in calls


def test_refused_program_prints_no_call(tmp_path):
    p = run(write(tmp_path / "p.ngc", "G0 X1\nG5.2 X2 F100\nM2\n"))
    assert p.returncode == 2
    assert p.stdout == ""
    assert "line 2, column 1" in p.stderr and "G5.2" in p.stderr


def test_bad_tool_table_and_var_file_are_refused(tmp_path):
    program = write(tmp_path / "p.ngc", "M2\n")
    p = run(program, "--tool-table", write(tmp_path / "bad.tbl", "T1 P1 Zx\n"))
    assert p.returncode == 2 and p.stdout == ""
    assert "bad.tbl: line 1" in p.stderr
    p = run(program, "--var-file", write(tmp_path / "bad.var", "5221 ten\n"))
    assert p.returncode == 2 and "bad.var: line 1" in p.stderr
    p = run(str(tmp_path / "missing.ngc"))
    assert p.returncode == 2 and "missing.ngc" in p.stderr


def moves_program(lines: int, tail: str = "M2\n") -> str:
    return "F600\n" + "".join(f"G1 X{k % 97}.{k % 10} Y{k % 89}.5 Z-{k % 3}\n" for k in range(lines)) + tail


def test_a_refusal_after_many_calls_prints_none_of_them(tmp_path):
    # The calls are spooled as they are made: the 20,000 moves before line 20003
    # must still not reach stdout.
    p = run(write(tmp_path / "p.ngc", moves_program(20000, "G0 X0\nG5.2 X1\nM2\n")))
    assert p.returncode == 2
    assert p.stdout == ""
    assert "line 20003, column 1" in p.stderr and "G5.2" in p.stderr


def peak_rss_kib(args: list[str], out: Path) -> int:
    """The one child's peak resident set (kernel accounting, not sampled)."""
    with out.open("w") as sink:
        proc = subprocess.Popen(args, stdout=sink, stderr=subprocess.DEVNULL, stdin=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)
    assert os.waitstatus_to_exitcode(status) == 0
    return usage.ru_maxrss


def test_memory_does_not_grow_with_the_calls(tmp_path):
    # 16 times the moves: the peak grows by the program's text and a little
    # per line, not by the calls (a held call costs about 200 bytes, its
    # text on stdout about 66: 28 times the program's size before the calls
    # were streamed).
    small, large = tmp_path / "small.ngc", tmp_path / "large.ngc"
    small.write_text(moves_program(20000))
    large.write_text(moves_program(320000))
    tnvctl = canon_compare.env_tnvctl()
    peaks = [peak_rss_kib([tnvctl, "gcode", "canon", str(p)], tmp_path / "out.txt") for p in (small, large)]
    out_bytes = (tmp_path / "out.txt").stat().st_size
    extra_program_kib = (large.stat().st_size - small.stat().st_size) / 1024
    assert out_bytes > 2 * large.stat().st_size  # the calls are more than the program
    assert peaks[1] - peaks[0] < 3 * extra_program_kib, (peaks, extra_program_kib)
