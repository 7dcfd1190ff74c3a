#!/usr/bin/env bash
# The kernel stage's version choice (scripts/kernel-vm/pick-version.sh)
# against a stub apt-cache that offers what Debian's archive offered on a
# day when one kernel's packages stood at different versions: the image's
# exact version where it exists, else the newest of the same upstream
# release, else a failure that names the package and what is offered.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
stub=$(mktemp -d)
trap 'rm -rf "$stub"' EXIT
cat >"$stub/apt-cache" <<'STUB'
#!/usr/bin/env bash
[[ $1 == madison ]] || exit 1
case $2 in
  linux-headers-6.1.0-56-amd64) v="6.1.192-2" ;;
  linux-kbuild-6.1) v="6.1.192-3 6.1.176-1" ;;
  linux-source-6.1) v="6.1.192-10 6.1.192-3 6.1.192-2 6.1.190-1" ;;
  linux-tools-6.1) v="6.1.192-9 6.1.192-10 6.1.190-4" ;;
  linux-missing-6.1) v="6.1.176-1 6.1.190-1" ;;
  *) v="" ;;
esac
for x in $v; do echo " $2 | $x | http://archive.invalid bookworm/main amd64 Packages"; done
STUB
chmod +x "$stub/apt-cache"
export PATH="$stub:$PATH"
log() { :; }
die() { echo "FAIL: $*" >&2; exit 1; }
source "$here/../../scripts/kernel-vm/pick-version.sh"

failures=0
checks=0
expect() {  # package, image version, expected pick
  local got
  checks=$((checks + 1))
  got=$(pick_version "$1" "$2") || got="(failed)"
  if [[ "$got" != "$3" ]]; then
    echo "FAILED: $1 for $2: picked $got, expected $3"
    failures=$((failures + 1))
  fi
}
expect linux-headers-6.1.0-56-amd64 6.1.192-2 6.1.192-2   # exact
expect linux-source-6.1 6.1.192-2 6.1.192-2               # exact, though newer exist
expect linux-kbuild-6.1 6.1.192-2 6.1.192-3               # the case that broke a fresh machine
expect linux-tools-6.1 6.1.192-2 6.1.192-10               # newest by Debian's ordering, not by text
# None of the same upstream release: a failure naming the package and the offer.
checks=$((checks + 1))
if msg=$(pick_version linux-missing-6.1 6.1.192-2 2>&1); then
  echo "FAILED: linux-missing-6.1 picked '$msg' though no 6.1.192 is offered"
  failures=$((failures + 1))
elif [[ "$msg" != *linux-missing-6.1* || "$msg" != *"6.1.176-1 6.1.190-1"* ]]; then
  echo "FAILED: the refusal does not name the package and the versions offered: $msg"
  failures=$((failures + 1))
fi
echo "$((checks - failures)) passed, ${failures} failed"
[[ $failures -eq 0 ]]
