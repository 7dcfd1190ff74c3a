"""python3 -m tnvplot KIND INPUT... OUTPUT [--title T] [--label L ...]"""

import argparse
import sqlite3
import sys


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m tnvplot", description="Draw a TNV-40 host figure.")
    parser.add_argument("kind", help="circle, panels (plot-data JSON), path (path CSV), capture (capture CSVs), bode (freq-response JSON) "
                        "or campaign (a merged campaign.sqlite)")
    parser.add_argument("files", nargs="+", metavar="FILE", help="the inputs, then the output (.svg, .png or .pdf)")
    parser.add_argument("--title", default="", help="figure title (path and capture)")
    parser.add_argument("--label", action="append", default=[], help="row label per capture CSV")
    parser.add_argument("--option", action="append", default=[], metavar="KEY=VALUE",
                        help="a figure's own setting (campaign: metric=max_um, limit=5)")
    args = parser.parse_args(argv)
    if len(args.files) < 2:
        parser.error("give the input file(s) and then the output file")
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError as e:
        print(f"tnvplot: {e.name} is missing: install Debian's python3-{e.name} "
              f"(apt-get install python3-matplotlib python3-numpy)", file=sys.stderr)
        return 3
    from tnvplot.render import render
    try:
        options = dict(o.split("=", 1) for o in args.option if "=" in o)
        render(args.kind, args.files[:-1], args.files[-1], args.title, args.label, options)
    except (OSError, ValueError, KeyError, sqlite3.Error) as e:
        print(f"tnvplot: {args.files[-1]}: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
