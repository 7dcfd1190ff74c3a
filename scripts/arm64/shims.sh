#!/usr/bin/env bash
# CMake config shims for the header-only dependencies (Eigen, toml++,
# CLI11, nlohmann-json) of an aarch64 cross build: only their own include
# dirs (never the host's /usr/include, whose libc headers are x86-64's),
# so no arm64 multiarch -dev packages are needed. Used by scripts/arm64.sh
# and scripts/package.sh.
#   scripts/arm64/shims.sh DIR     prints the -D<Pkg>_DIR arguments
set -euo pipefail
shim=$1
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
echo "-DEigen3_DIR=$shim/Eigen3 -Dtomlplusplus_DIR=$shim/tomlplusplus -DCLI11_DIR=$shim/CLI11 -Dnlohmann_json_DIR=$shim/nlohmann_json"
