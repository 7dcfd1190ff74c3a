#!/usr/bin/env bash
# The CMake package from an installed tree (ctest package.install):
#   tests/package/check_install.sh BUILD_DIR WORK_DIR
# 1. `cmake --install --prefix` of every component writes only under the
#    prefix (install_manifest.txt);
# 2. a project outside the tree configures with the default generator,
#    finds tnv with find_package(tnv CONFIG REQUIRED), links tnv::firmware
#    and tnv::can_host, and its programs run.
set -euo pipefail
build=$(cd "$1" && pwd)
work=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "${work}"
mkdir -p "${work}"
prefix=${work}/prefix

cmake --install "${build}" --prefix "${prefix}" >"${work}/install.log"
outside=$(grep -v "^${prefix}/" "${build}/install_manifest.txt" || true)
if [[ -n ${outside} ]]; then
  echo "installed outside the prefix ${prefix}:" >&2
  echo "${outside}" >&2
  exit 1
fi
for f in tnv/tnvConfig.cmake tnv/firmware/can/param_table.hpp tnv/tools/can/node_client.hpp; do
  [[ -n $(find "${prefix}" -path "*/${f}" -print -quit) ]] || { echo "not installed: */${f}" >&2; exit 1; }
done

# No -G: the default generator, as a user's plain `cmake -S -B` gets.
env -u CMAKE_GENERATOR cmake -S "${here}/consumer" -B "${work}/consumer" -DCMAKE_PREFIX_PATH="${prefix}" \
  -DCMAKE_BUILD_TYPE=Release >"${work}/configure.log"
cmake --build "${work}/consumer" -j 2 >"${work}/build.log"
"${work}/consumer/firmware_only"
"${work}/consumer/emulated_node" "${work}/params.bin"
