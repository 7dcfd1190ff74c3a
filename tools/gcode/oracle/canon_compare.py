"""Call-by-call comparison of `tnvctl gcode canon` against LinuxCNC's
standalone interpreter `rs274 -g` (Debian's linuxcnc-uspace), the oracle
nobody here wrote (docs/gcode.md).

rs274 is an inch machine: it reads a tool table's lengths and a .var file's
offsets as inches. Both are written here from one millimetre source, the
millimetre copy for tnvctl and an inch copy for rs274, so both interpreters
see the same tools and offsets: every number to the last bit of its double
(a tool diameter 1e-8 mm short moved the centre of an ill-conditioned
compensated entry arc by 1.4e-4 mm; docs/gcode.md).
"""
from __future__ import annotations

import dataclasses
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

MM_PER_INCH = 25.4
# Both print 4 decimals in the program's units: two values that agree to
# well under 1e-4 can still round one last digit apart.
TOLERANCE = 1.0001e-4
_RS274_LINE = re.compile(r"^\s*\d+ N\S* +(\S.*)$")  # "   12 N..... CALL" or "   12 N170   CALL"
_NUMBER = re.compile(r"-?\d+\.\d+|-?\d+")


def rs274_path() -> str | None:
    return shutil.which("rs274")


@dataclasses.dataclass
class Run:
    ok: bool
    calls: list[str]
    error: str


def exact(value: float) -> str:
    """A number as text that reads back as the same double (no exponent: both tables' readers take it)."""
    text = f"{value:.17f}"
    while len(text) < 64 and float(text) != value:
        text = f"{value:.{len(text.split('.')[1]) + 3}f}"
    return text


def write_tool_tables(tools: list[tuple[int, float, float]], directory: Path) -> tuple[Path, Path]:
    """(tool, length mm, diameter mm) rows as a millimetre and an inch table."""
    mm, inch = directory / "tools-mm.tbl", directory / "tools-inch.tbl"
    mm.write_text("".join(f"T{t} P{t} Z{exact(z)} D{exact(d)} ;tool {t}\n" for t, z, d in tools))
    inch.write_text("".join(f"T{t} P{t} Z{exact(z / MM_PER_INCH)} D{exact(d / MM_PER_INCH)} ;tool {t}\n"
                            for t, z, d in tools))
    return mm, inch


def write_var_files(values: dict[int, float], directory: Path) -> tuple[Path, Path]:
    """Parameters (number -> millimetres, or a plain number for 5220/5210) as mm and inch .var files."""
    unitless = {5210, 5220}
    mm, inch = directory / "params-mm.var", directory / "params-inch.var"
    mm.write_text("".join(f"{n}\t{exact(v)}\n" for n, v in sorted(values.items())))
    inch.write_text("".join(f"{n}\t{exact(v if n in unitless else v / MM_PER_INCH)}\n"
                            for n, v in sorted(values.items())))
    return mm, inch


def run_rs274(program: Path, tool_table: Path, var_file: Path | None = None, timeout: float = 60.0) -> Run:
    # A .var file rs274 may rewrite at the end: give it a copy.
    with tempfile.TemporaryDirectory() as tmp:
        args = ["rs274", "-g", "-t", str(tool_table)]
        if var_file is not None:
            copy = Path(tmp) / "params.var"
            shutil.copy(var_file, copy)
            args += ["-v", str(copy)]
        else:
            # Without -v rs274 reads and writes rs274ngc.var in its directory.
            args += ["-v", str(Path(tmp) / "rs274ngc.var")]
            (Path(tmp) / "rs274ngc.var").write_text("")
        args.append(str(program.resolve()))
        # rs274 keeps its tool table in $HOME/.tool.mmap, shared by every
        # rs274 of that user: two at once would read each other's tools.
        env = dict(os.environ, HOME=tmp)
        p = subprocess.run(args, cwd=program.resolve().parent, stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, timeout=timeout, errors="replace", env=env)
    calls = [m.group(1) for m in map(_RS274_LINE.match, p.stdout.splitlines()) if m]
    # The driver resets the interpreter after the run: not the program's calls.
    while calls and calls[-1] == "ON_RESET()":
        calls.pop()
    return Run(p.returncode == 0, calls, p.stderr.replace("executing", "").strip())


def run_tnvctl(tnvctl: str, program: Path, tool_table: Path, var_file: Path | None = None,
               timeout: float = 60.0) -> Run:
    args = [tnvctl, "gcode", "canon", str(program.resolve()), "--tool-table", str(tool_table)]
    if var_file is not None:
        args += ["--var-file", str(var_file)]
    p = subprocess.run(args, cwd=program.resolve().parent, stdin=subprocess.DEVNULL, capture_output=True, text=True,
                       timeout=timeout, errors="replace")
    return Run(p.returncode == 0, p.stdout.splitlines() if p.returncode == 0 else [], p.stderr.strip())


def _numbers(call: str, ours: bool) -> list[float]:
    values = [float(x) for x in _NUMBER.findall(call)]
    # SET_TOOL_TABLE_ENTRY(pocket, tool, 9 offsets, front, back, orientation)
    # gives the offsets in the machine's units: millimetres for tnvctl,
    # inches for the standalone rs274. Compared in inches.
    if ours and call.startswith("SET_TOOL_TABLE_ENTRY(") and len(values) == 14:
        values[2:11] = [v / MM_PER_INCH for v in values[2:11]]
    return values


def same_call(a: str, b: str) -> bool:
    """a: tnvctl's call, b: rs274's."""
    if a == b and not a.startswith("SET_TOOL_TABLE_ENTRY("):
        return True
    if _NUMBER.sub("#", a) != _NUMBER.sub("#", b):
        return False
    return all(abs(x - y) <= TOLERANCE for x, y in zip(_numbers(a, True), _numbers(b, False)))


def first_difference(ours: list[str], theirs: list[str]) -> str | None:
    """None when the lists agree call by call, else where they part."""
    for k, (a, b) in enumerate(zip(ours, theirs)):
        if not same_call(a, b):
            return f"call {k + 1}: tnvctl {a!r} vs rs274 {b!r}"
    if len(ours) != len(theirs):
        k = min(len(ours), len(theirs))
        extra = ours[k] if len(ours) > k else theirs[k]
        who = "tnvctl" if len(ours) > k else "rs274"
        return f"call {k + 1}: only {who} has {extra!r} ({len(ours)} vs {len(theirs)} calls)"
    return None


def compare(tnvctl: str, program: Path, tables: tuple[Path, Path], var_files: tuple[Path, Path] | None = None,
            timeout: float = 60.0) -> str | None:
    """None when both agree (both run with the same calls, or both refuse), else why not."""
    theirs = run_rs274(program, tables[1], var_files[1] if var_files else None, timeout)
    ours = run_tnvctl(tnvctl, program, tables[0], var_files[0] if var_files else None, timeout)
    if not theirs.ok and not ours.ok:
        return None
    if theirs.ok != ours.ok:
        return (f"rs274 {'ran' if theirs.ok else 'refused: ' + theirs.error!r}, "
                f"tnvctl {'ran' if ours.ok else 'refused: ' + ours.error!r}")
    return first_difference(ours.calls, theirs.calls)


def default_tools(directory: Path) -> tuple[Path, Path]:
    """Tools 1..20: length 2.5 mm x n, diameter 1.25 mm x n."""
    return write_tool_tables([(t, 2.5 * t, 1.25 * t) for t in range(1, 21)], directory)


def env_tnvctl() -> str | None:
    exe = os.environ.get("TNVCTL_EXE")
    return str(Path(exe).resolve()) if exe and os.access(exe, os.X_OK) else None
