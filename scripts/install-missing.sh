#!/usr/bin/env bash
# Installs the named Debian packages that are not installed yet; used
# for the build (install-deps.sh) and for the stages that need more:
# kernel-vm, arm64, fuzz.
# Usage: scripts/install-missing.sh TAG PACKAGE...
set -euo pipefail
tag=$1; shift

missing=()
for p in "$@"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "[${tag}] all $# packages present"
  exit 0
fi

sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "[${tag}] need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "[${tag}] installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
