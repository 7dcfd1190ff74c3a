#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs, and only the missing ones.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libgpiod-dev
  python3-canmatrix   # tests: an independent DBC parser decodes a recorded session
)

exec "$(dirname "$0")/install-missing.sh" deps "${packages[@]}"
