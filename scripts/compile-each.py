#!/usr/bin/env python3
"""Compiles every translation unit of a unity build on its own, syntax only.

The presets build with CMAKE_UNITY_BUILD, where a source that forgets an
include still compiles because an earlier file of its batch brought the
header in; the plain `cmake -S . -B build && cmake --build build` then
fails. This runs each source that a unity batch includes after its first (the
build itself compiled the first, and every source outside the batches, on
its own) through its own target's compile command with
-fsyntax-only: the same flags, warnings as errors, no object written, so a
missing include fails here, naming the file, without a second full build.

    scripts/compile-each.py build/release [-j N] [--prefer build/asan] [PATH_PREFIX ...]

(with prefixes, only the sources under them, e.g. `tools/tnvctl`).
`--prefer TREE` takes a source's command from TREE wherever TREE compiles
that source (building the precompiled headers its build skipped, such as
the asan tree's tnv-hil and tnvctl ones), and from the first tree
otherwise. The CI passes the asan tree (clang): clang maps a precompiled
header lazily (0.05 CPU-s a source) where GCC reads all of it (0.5 to
1.0: the test suites' header is 184 MB), so the check takes 195 CPU-s
instead of 431 on a tree of e13a58f (docs/notes.md "CI time"). Both compilers read the
same libstdc++ and project headers, so a missing include fails either way.
`--optimize` compiles each for real (object to /dev/null), which also
shows the warnings only the optimizer gives, e.g. GCC 12's false
-Wrestrict of d1b5805; not in CI (about twice the time), run by hand over
the sources a change touched.

Needs the build's compile_commands.json (CMAKE_EXPORT_COMPILE_COMMANDS is
on in CMakeLists.txt) and its generated headers, so it runs after the build.
Exit status 0 when every source compiles, 1 otherwise, 2 on bad arguments.
"""

import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

UNITY_INCLUDE = re.compile(r'^#include "(.+)"\s*$', re.MULTILINE)


def units(entry, whole_batch=False):
    """The sources of one compile_commands entry that the build did not
    already compile on their own: a unity batch's second and later files
    (its first sees nothing before it but what the plain build sees, and a
    source outside the batches is compiled alone anyway). `whole_batch`
    (for --optimize): its first too, whose optimizer saw the later files."""
    path = entry["file"]
    if os.path.basename(os.path.dirname(path)) == "Unity" and re.match(r"unity_\d+_cxx\.cxx$", os.path.basename(path)):
        with open(path, encoding="utf-8") as f:
            return UNITY_INCLUDE.findall(f.read())[0 if whole_batch else 1:]
    return []


def syntax_command(entry, source, optimize=False):
    """The entry's command for `source`: -fsyntax-only, no object file; with
    `optimize`, a whole compile to /dev/null (the optimizer's warnings too)."""
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    out, skip = [], False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-c", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-MD", "-MMD") or a == entry["file"]:
            continue
        out.append(a)
    return out + (["-c", "-o", os.devnull, source] if optimize else ["-fsyntax-only", source])


def load(build_dir):
    """The tree's compile_commands.json entries, or None without one."""
    db = os.path.join(build_dir, "compile_commands.json")
    if not os.path.isfile(db):
        return None
    with open(db, encoding="utf-8") as f:
        return json.load(f)


def missing_pchs(command):
    """The clang precompiled headers the command loads that are not built
    (a target the tree's build skipped, e.g. the asan tree's tnvctl)."""
    args = [a for a in command if a != "-Xclang"]  # CMake writes -Xclang -include-pch -Xclang FILE
    return [b for a, b in zip(args, args[1:]) if a == "-include-pch" and not os.path.isfile(b)]


def pch_built(command):
    return not missing_pchs(command)


def commands_by_source(entries, optimize):
    """source -> (directory, command) for every source the tree compiles,
    in a unity batch or alone, with its first target's flags."""
    found = {}
    for entry in entries:
        sources = units(entry, whole_batch=True) or [entry["file"]]
        for source in sources:
            if source not in found:
                found[source] = (entry["directory"], syntax_command(entry, source, optimize))
    return found


def build_pchs(tree, commands):
    """Builds the precompiled headers that the commands load and the tree's
    build skipped (tnv-hil's and tnvctl's in the asan tree: 3 CPU seconds
    each, against 1 s more a source for GCC's); False if that fails."""
    pchs = sorted({p for _, command in commands for p in missing_pchs(command)})
    if not pchs:
        return True
    targets = [os.path.relpath(p, os.path.abspath(tree)) for p in pchs]
    r = subprocess.run(["cmake", "--build", tree, "--target", *targets], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"compile-each: could not build {', '.join(targets)} in {tree}; those sources keep the first tree's "
              f"flags:\n{r.stdout[-2000:]}{r.stderr[-2000:]}", file=sys.stderr)
    return r.returncode == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("build_dir")
    parser.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--optimize", action="store_true",
                        help="compile each for real, object to /dev/null: also the warnings only the optimizer "
                        "gives (GCC 12's -Wrestrict), at about twice the time")
    parser.add_argument("--prefer", metavar="TREE",
                        help="take each source's command from this tree where it compiles the source "
                        "(the asan tree: clang's precompiled headers load lazily)")
    parser.add_argument("prefixes", nargs="*", help="only the sources under these paths (relative to the source tree)")
    opts = parser.parse_intermixed_args()
    entries = load(opts.build_dir)
    preferred = {}  # source -> (directory, command) in the --prefer tree
    if opts.prefer:
        prefer_entries = load(opts.prefer)
        if prefer_entries is None:
            print(f"compile-each: no compile_commands.json in {opts.prefer} (configure and build first)", file=sys.stderr)
            return 2
        preferred = commands_by_source(prefer_entries, opts.optimize)
    if entries is None:
        print(f"compile-each: no compile_commands.json in {opts.build_dir} (configure and build first)", file=sys.stderr)
        return 2
    roots = [os.path.abspath(p) for p in opts.prefixes]

    def wanted(source):
        return not roots or any(source == r or source.startswith(r.rstrip("/") + "/") for r in roots)

    jobs = {}  # source -> (directory, command): each source once, with its first target's flags
    fallback = {}  # source -> the first tree's (directory, command), for one taken from --prefer's
    for entry in entries:
        for source in units(entry, opts.optimize):
            if source.endswith((".cpp", ".cc", ".cxx")) and wanted(source) and source not in jobs:
                own = (entry["directory"], syntax_command(entry, source, opts.optimize))
                jobs[source] = preferred.get(source, own)
                if source in preferred:
                    fallback[source] = own
    # A clang precompiled header that the tree's build skipped is built now.
    if fallback and not build_pchs(opts.prefer, [jobs[source] for source in fallback]):
        for source, own in fallback.items():
            if not pch_built(jobs[source][1]):
                jobs[source] = own
    build_pchs(opts.build_dir, [job for source, job in jobs.items() if source not in fallback])
    from_preferred = sum(1 for source in fallback if jobs[source] is not fallback[source])

    def check(item):
        source, (directory, command) = item
        r = subprocess.run(command, cwd=directory, capture_output=True, text=True)
        return source, r.returncode, r.stderr

    started = time.monotonic()
    failed = []
    with ThreadPoolExecutor(max_workers=max(1, opts.jobs)) as pool:
        for source, code, err in pool.map(check, sorted(jobs.items())):
            if code != 0:
                failed.append(source)
                lines = err.splitlines()
                print(f"--- {source} does not compile on its own:", file=sys.stderr)
                print("\n".join(lines[:40] + (["..."] if len(lines) > 40 else [])), file=sys.stderr)
    print(f"compile-each: {len(jobs) - len(failed)} of {len(jobs)} sources compile on their own "
          f"({time.monotonic() - started:.0f} s, {opts.jobs} jobs"
          + (f"; {from_preferred} with {opts.prefer}'s flags, the rest with {opts.build_dir}'s)" if opts.prefer else ")"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
