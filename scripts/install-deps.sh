#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs, and only the missing ones.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgpiod-dev
  python3-canmatrix   # tests: an independent DBC parser decodes a recorded session
  python3-matplotlib python3-numpy   # the figures: --plot runs tools/plot/tnvplot
  python3-pytest      # tests: the plotting package (ctest -L plot) and the Python module (ctest -L python)
  python3-dev pybind11-dev python3-pandas   # the Python module tnv (tools/python): built, and capture_frame()
  libsqlite3-dev      # tnv-hil campaign: the merged results (tools/campaign)
  parallel            # tests: a campaign's shards run by GNU parallel (ctest -R Campaign)
  libcpp-httplib-dev libjs-chart.js   # tnvctl serve (tools/serve): the HTTP/SSE server, the page's plots
  libssl-dev   # tnvctl serve --tls-cert/--tls-key: cpp-httplib with OpenSSL
  chromium chromium-driver python3-selenium   # tests: the tuning page in a headless browser (ctest -L web)
)

exec "$(dirname "$0")/install-missing.sh" deps "${packages[@]}"
