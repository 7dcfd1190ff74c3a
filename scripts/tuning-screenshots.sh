#!/usr/bin/env bash
# The tuning guide's screenshots of the live tuning page (docs/img/tuning-*.png),
# taken by the page's browser test in Debian's headless chromium against
# `tnvctl --emu serve` (the emulated node; the Bode view from the test's
# result file tools/serve/tests/bode_fixture.json).
#   scripts/tuning-screenshots.sh [BUILD_DIR]    (default build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
tnvctl=$build/tools/tnvctl
[[ -x $tnvctl ]] || { echo "tuning-screenshots: no $tnvctl (build first: cmake --build $build --target tnvctl)" >&2; exit 2; }
TNVCTL_EXE=$tnvctl TNV_SCREENSHOT_DIR=docs/img /usr/bin/python3 -B -m pytest -q -s -p no:cacheprovider tools/serve/tests
ls -l docs/img/tuning-*.png
