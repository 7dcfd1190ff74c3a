#!/usr/bin/env bash
# The board package's systemd units (ctest package.units, a few seconds):
#   tests/package/check_units.sh SOURCE_DIR WORK_DIR
# 1. systemd-analyze verify: both units parse (ExecStart pointed at
#    /bin/true, the template as the instance tnv-fw@can0);
# 2. systemd-analyze security --offline: exposure at most 4.0 for each;
# 3. the template differs from tnv-fw.service only in [Unit] and in the
#    --can %i of its command lines (the hardening is kept in step).
set -euo pipefail
src=$(cd "$1" && pwd)
work=$2
rm -rf "${work}"
mkdir -p "${work}"
unit=${src}/packaging/tnv-fw.service
template=${src}/packaging/tnv-fw@.service

sed 's#/usr/bin/tnv-fw#/bin/true#' "${unit}" >"${work}/tnv-fw.service"
sed 's#/usr/bin/tnv-fw#/bin/true#' "${template}" >"${work}/tnv-fw@can0.service"
systemd-analyze verify --man=no "${work}/tnv-fw.service" "${work}/tnv-fw@can0.service"

# --threshold is in tenths of the printed exposure: 40 = 4.0.
report=$(systemd-analyze security --offline=true --threshold=40 --no-pager "${unit}" "${template}") || {
  echo "${report}" >&2
  echo "exposure above 4.0" >&2
  exit 1
}
grep 'Overall exposure' <<<"${report}"

service_section() { sed -n '/^\[Service\]/,/^\[Install\]/p' "$1" | grep -v '^#' | sed 's/ --can %i//'; }
if ! diff <(service_section "${unit}") <(service_section "${template}"); then
  echo "tnv-fw@.service's [Service] differs from tnv-fw.service's (beyond --can %i)" >&2
  exit 1
fi
echo "units ok"
