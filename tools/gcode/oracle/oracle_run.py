"""Run the oracle comparison from the command line (docs/gcode.md):

  python3 tools/gcode/oracle/oracle_run.py samples --tnvctl build/release/tools/tnvctl
  python3 tools/gcode/oracle/oracle_run.py random --tnvctl ... --count 10000 --seed 1

`samples` prints the agreement table of LinuxCNC's sample programs;
`random` compares generated programs and prints each disagreement's seed.
Exit status 1 when anything disagrees.
"""
from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import canon_compare  # noqa: E402
import random_program  # noqa: E402

SAMPLE_DIR = Path("/usr/share/linuxcnc/ncfiles")
# The 25 non-lathe samples LinuxCNC's interpreter runs to the end with motion
# (given tools 1..20 in the table).
SAMPLES = ["3D_Chips", "3dtest", "arcspiral", "b-index", "cds", "comp-g1", "comp", "comp311", "comp311_2", "daisy",
           "flowsnake", "gmoccapy_2_tools_with_cutter_radius_compensation", "gridprobe", "hole-circle", "mmount",
           "plasmatest", "polar", "skeleton", "smartprobe", "spiral", "systems", "toplevel", "tort",
           "useful-subroutines", "x-trim"]


def samples(tnvctl: str) -> int:
    disagree = 0
    with tempfile.TemporaryDirectory() as tmp:
        tables = canon_compare.default_tools(Path(tmp))
        for name in SAMPLES:
            why = canon_compare.compare(tnvctl, SAMPLE_DIR / f"{name}.ngc", tables)
            disagree += why is not None
            print(f"{name:50s} {'agrees' if why is None else 'differs: ' + why}")
    print(f"{len(SAMPLES) - disagree} of {len(SAMPLES)} agree call by call")
    return 1 if disagree else 0


def random_run(tnvctl: str, count: int, seed: int) -> int:
    failures = 0
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as tmp:
        tables = canon_compare.default_tools(Path(tmp))
        program = Path(tmp) / "random.ngc"
        for k in range(seed, seed + count):
            program.write_text(random_program.random_program(k))
            why = canon_compare.compare(tnvctl, program, tables)
            if why is not None:
                failures += 1
                print(f"seed {k}: {why}")
    print(f"{count - failures} of {count} random programs agree (seeds {seed}..{seed + count - 1}, "
          f"{time.monotonic() - start:.1f} s)")
    return 1 if failures else 0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("what", choices=["samples", "random"])
    ap.add_argument("--tnvctl", required=True)
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    if canon_compare.rs274_path() is None:
        print("rs274 not found: apt-get install linuxcnc-uspace", file=sys.stderr)
        return 2
    tnvctl = str(Path(a.tnvctl).resolve())
    return samples(tnvctl) if a.what == "samples" else random_run(tnvctl, a.count, a.seed)


if __name__ == "__main__":
    sys.exit(main())
