"""Interpreting speed against LinuxCNC's interpreter, side by side (docs/gcode.md):

  python3 tools/gcode/oracle/canon_speed.py --tnvctl build/release/tools/tnvctl [--lines 1000000] [--runs 5]

Writes a 3-D surfacing program of LINES feed moves (zig-zag rows over a
100 mm patch, Z on a smooth surface, as a CAM post writes one), checks
that `tnvctl gcode canon` and `rs274 -g` agree on it call by call, then
runs the two in turn RUNS times (A B A B ...: a drift of the machine's
speed hits both) and prints each one's CPU seconds (user + system of the
finished process, the operating system's own accounting), their medians,
the lines per CPU second and the median of the pairwise ratios rs274 /
tnvctl. Both write their calls to a file, as `> FILE` would. Exit status
1 when the two disagree.
"""
from __future__ import annotations

import argparse
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import canon_compare  # noqa: E402


def surfacing_program(lines: int) -> str:
    rows = max(1, round(math.sqrt(lines)))
    per_row = max(1, lines // rows)
    out = ["%", "(3-D surfacing)", "G21 G90 G17 G94 G40 G49 G54", "T1 M6", "G43 H1", "S8000 M3", "G0 Z10", "G0 X0 Y0",
           "G1 Z-1 F600"]
    step = 100.0 / per_row
    for r in range(rows):
        y = r * 100.0 / rows
        for k in range(per_row):
            x = (k if r % 2 == 0 else per_row - 1 - k) * step
            z = -1.0 - 0.5 * math.sin(x * 0.05) * math.cos(y * 0.05)
            out.append(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f}")
    out += ["G0 Z10", "M5", "M30", "%"]
    return "\n".join(out) + "\n"


def cpu_seconds(args: list[str], cwd: Path, out: Path, env: dict[str, str] | None = None) -> float:
    """The finished child's user + system seconds (its own accounting)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with out.open("w") as sink:
        subprocess.run(args, cwd=cwd, stdin=subprocess.DEVNULL, stdout=sink, stderr=subprocess.STDOUT, env=env,
                       check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--tnvctl", required=True)
    ap.add_argument("--lines", type=int, default=1_000_000)
    ap.add_argument("--runs", type=int, default=5)
    opts = ap.parse_args()
    opts.tnvctl = str(Path(opts.tnvctl).resolve())  # the runs start in a temporary directory
    if canon_compare.rs274_path() is None:
        print("rs274 not found: apt-get install linuxcnc-uspace", file=sys.stderr)
        return 2
    if opts.lines < 1 or opts.runs < 1:
        print("--lines and --runs must be >= 1", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp_text:
        tmp = Path(tmp_text)
        program = tmp / "surfacing.ngc"
        program.write_text(surfacing_program(opts.lines))
        tables = canon_compare.default_tools(tmp)
        why = canon_compare.compare(opts.tnvctl, program, tables, timeout=600.0)
        if why is not None:
            print(f"the two disagree on the program: {why}")
            return 1
        var = tmp / "rs274ngc.var"
        ours_args = [opts.tnvctl, "gcode", "canon", str(program), "--tool-table", str(tables[0])]
        theirs_args = ["rs274", "-g", "-t", str(tables[1]), "-v", str(var), str(program)]
        # rs274 keeps its tool table under $HOME (canon_compare.run_rs274).
        theirs_env = dict(os.environ, HOME=str(tmp))
        ours, theirs = [], []
        for _ in range(opts.runs):
            ours.append(cpu_seconds(ours_args, tmp, tmp / "ours.txt"))
            var.write_text("")
            theirs.append(cpu_seconds(theirs_args, tmp, tmp / "theirs.txt", theirs_env))
        ratios = [t / o for o, t in zip(ours, theirs)]
        n = program.read_text().count("\n")
        print(f"program: {n} lines ({program.stat().st_size} bytes), {opts.runs} runs each, CPU seconds")
        for name, runs in (("tnvctl gcode canon", ours), ("rs274 -g", theirs)):
            med = statistics.median(runs)
            print(f"{name:20s} median {med:7.3f} s  (min {min(runs):.3f}, max {max(runs):.3f})  "
                  f"{n / med:12,.0f} lines/s")
        print(f"rs274 / tnvctl: median {statistics.median(ratios):.2f} (min {min(ratios):.2f}, max {max(ratios):.2f})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
