"""`tnvctl gcode canon` as a command (no rs274 needed): output, refusals,
options."""
from __future__ import annotations

import json
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
