#!/usr/bin/env bash
# CMake config shims for the header-only dependencies (Eigen, toml++,
# CLI11, nlohmann-json) of an aarch64 cross build: only their own include
# dirs (never the host's /usr/include, whose libc headers are x86-64's),
# so no arm64 multiarch -dev packages are needed. Used by scripts/arm64.sh
# and scripts/package.sh.
#   scripts/arm64/shims.sh DIR [--python]   prints the -D<Pkg>_DIR arguments
# --python adds a pybind11 shim for the Python module: Debian's pybind11
# headers, the shared Python headers and the arm64 pyconfig.h of
# libpython3-dev:arm64 (multiarch, headers only), and the module suffix of
# the target's python3 (cpython-3XY-aarch64-linux-gnu).
set -euo pipefail
shim=$1
python=0
[[ ${2:-} == --python ]] && python=1
mkdir -p "$shim/include"
ln -sfn /usr/include/eigen3 "$shim/include/eigen3"
for d in toml++ CLI nlohmann; do ln -sfn "/usr/include/$d" "$shim/include/$d"; done
write_shim() {  # NAME VERSION TARGET INCLUDE_DIR [DEFINES]
  mkdir -p "$shim/$1"
  cat > "$shim/$1/$1Config.cmake" <<EOC
if(NOT TARGET $3)
  add_library($3 INTERFACE IMPORTED)
  set_target_properties($3 PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "$4" INTERFACE_COMPILE_DEFINITIONS "${5:-}")
endif()
set($1_FOUND TRUE)
EOC
  cat > "$shim/$1/$1ConfigVersion.cmake" <<EOC
set(PACKAGE_VERSION "$2")
if(PACKAGE_FIND_VERSION VERSION_GREATER PACKAGE_VERSION)
  set(PACKAGE_VERSION_COMPATIBLE FALSE)
else()
  set(PACKAGE_VERSION_COMPATIBLE TRUE)
endif()
EOC
}
write_shim Eigen3 3.4.0 Eigen3::Eigen "$shim/include/eigen3"
write_shim tomlplusplus 3.3.0 tomlplusplus::tomlplusplus "$shim/include" "TOML_HEADER_ONLY=1"
write_shim CLI11 2.3.0 CLI11::CLI11 "$shim/include"
write_shim nlohmann_json 3.11.2 nlohmann_json::nlohmann_json "$shim/include"
args="-DEigen3_DIR=$shim/Eigen3 -Dtomlplusplus_DIR=$shim/tomlplusplus -DCLI11_DIR=$shim/CLI11 -Dnlohmann_json_DIR=$shim/nlohmann_json"
if ((python)); then
  py=$(/usr/bin/python3 -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')
  [[ -f /usr/include/aarch64-linux-gnu/python$py/pyconfig.h ]] \
    || { echo "shims.sh: no arm64 pyconfig.h for python$py (libpython$py-dev:arm64)" >&2; exit 1; }
  inc=$shim/python/include
  mkdir -p "$inc/aarch64-linux-gnu" "$shim/pybind11"
  ln -sfn /usr/include/pybind11 "$inc/pybind11"
  ln -sfn "/usr/include/python$py" "$inc/python$py"
  ln -sfn "/usr/include/aarch64-linux-gnu/python$py" "$inc/aarch64-linux-gnu/python$py"
  cat > "$shim/pybind11/pybind11Config.cmake" <<EOC
# pybind11 for the aarch64 cross build: headers only (the host's config
# would put the host's /usr/include, x86-64 libc headers, on the path).
if(NOT TARGET pybind11::module)
  add_library(pybind11::module INTERFACE IMPORTED)
  set_target_properties(pybind11::module PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "$inc;$inc/python$py")
endif()
set(pybind11_FOUND TRUE)
function(pybind11_add_module name)
  cmake_parse_arguments(arg "MODULE;NO_EXTRAS" "" "" \${ARGN})
  add_library(\${name} MODULE \${arg_UNPARSED_ARGUMENTS})
  target_link_libraries(\${name} PRIVATE pybind11::module)
  set_target_properties(\${name} PROPERTIES PREFIX "" SUFFIX ".cpython-${py/./}-aarch64-linux-gnu.so"
                        CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
endfunction()
EOC
  cat > "$shim/pybind11/pybind11ConfigVersion.cmake" <<EOC
set(PACKAGE_VERSION "2.10.3")
set(PACKAGE_VERSION_COMPATIBLE TRUE)
EOC
  args+=" -Dpybind11_DIR=$shim/pybind11 -DTNV_BUILD_PYTHON=ON"
fi
echo "$args"
