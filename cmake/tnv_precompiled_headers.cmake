# The heavy third-party headers, parsed once per target instead of once per
# translation unit (CLI11 about 3 s of parsing, nlohmann/json 2 s, Eigen
# 1.7 s). Every build uses them, the plain `cmake -S . -B build` too, so
# scripts/compile-each.py (each source on its own, syntax only) checks
# exactly what that build compiles, at a fraction of the cost.
# httplib.h stays out: its <resolv.h> macro `_res` clashes with Eigen, and
# its OpenSSL switch is a definition its users set themselves.
# Eigen goes in wherever most of a target's sources reach it through the
# firmware's headers (the controllers, the observer and the adaptive loops
# hold Eigen matrices): 2.2 s of parsing per source that includes it, about
# 0.03 s to load for one that does not.
set(tnv_pch_cli <CLI/CLI.hpp> <nlohmann/json.hpp>)
set(tnv_pch_cli_eigen <CLI/CLI.hpp> <nlohmann/json.hpp> <Eigen/Dense>)
set(tnv_pch_json <nlohmann/json.hpp>)
set(tnv_pch_json_eigen <nlohmann/json.hpp> <Eigen/Dense>)
set(tnv_pch_eigen <Eigen/Dense>)
set(tnv_precompiled
    tnv_firmware tnv_pch_eigen
    tnv-hil tnv_pch_cli_eigen
    tnvctl tnv_pch_cli_eigen
    tnv_cli tnv_pch_cli
    tnv_freq_response_cli tnv_pch_cli_eigen
    tnv_hil_lib tnv_pch_json_eigen
    tnv_can_host tnv_pch_json_eigen
    tnv_can_emu tnv_pch_eigen
    tnv_fw_lib tnv_pch_eigen
    tnv_protogen_lib tnv_pch_eigen
    tnv_score tnv_pch_json
    tnv_serve tnv_pch_json_eigen
    tnv_tune tnv_pch_eigen
    tnv_campaign tnv_pch_json_eigen)
# The test suites share one precompiled header: tests/CMakeLists.txt, tnv_test_pch.
# Targets with the same headers share one too, built once in an object
# library and reused (REUSE_FROM, as the suites'): one parse instead of one
# per target (3 to 5 CPU-s each). Not one header for every target: GCC
# loads a header whole, and the largest (CLI11, nlohmann/json and Eigen,
# 196 MB) cost 2 to 4 CPU-s more per source in the libraries that had a
# smaller one (measured, docs/notes.md "CI time"). GCC takes a header only
# from a compile with the same code-generation flags, so only targets with
# the same options share (the firmware has its own: no exceptions, the work
# meter's coverage), the libraries that the Python module links
# (position-independent: tools/python/CMakeLists.txt) among themselves;
# with -Winvalid-pch and -Werror a mismatch stops the build.
list(LENGTH tnv_precompiled n)
math(EXPR last "${n} - 1")
set(tnv_pch_groups "")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET tnv_precompiled ${i} target)
  list(GET tnv_precompiled ${j} headers)
  # A target that this configuration does not build (no cpp-httplib, no tests) is skipped.
  if(NOT TARGET ${target})
    continue()
  endif()
  get_target_property(pic ${target} POSITION_INDEPENDENT_CODE)
  get_target_property(options ${target} COMPILE_OPTIONS)
  string(MD5 group "${headers} ${pic} ${options}")
  string(SUBSTRING ${group} 0 8 group)
  if(NOT DEFINED tnv_pch_targets_${group})
    list(APPEND tnv_pch_groups ${group})
    set(tnv_pch_headers_${group} ${headers})
  endif()
  list(APPEND tnv_pch_targets_${group} ${target})
endforeach()
foreach(group ${tnv_pch_groups})
  set(targets ${tnv_pch_targets_${group}})
  set(headers ${${tnv_pch_headers_${group}}})
  list(LENGTH targets count)
  if(count EQUAL 1)
    target_precompile_headers(${targets} PRIVATE ${headers})
    continue()
  endif()
  # The donor compiles like the group's first target (its options, its
  # position independence) and sees the same third-party headers.
  list(GET targets 0 first)
  set(donor ${tnv_pch_headers_${group}}_${group})
  add_library(${donor} OBJECT ${CMAKE_CURRENT_LIST_DIR}/pch_donor.cpp)
  get_target_property(options ${first} COMPILE_OPTIONS)
  get_target_property(pic ${first} POSITION_INDEPENDENT_CODE)
  if(options)
    target_compile_options(${donor} PRIVATE ${options})
  endif()
  if(pic)
    set_target_properties(${donor} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
  target_link_libraries(${donor} PRIVATE CLI11::CLI11 nlohmann_json::nlohmann_json Eigen3::Eigen tnv_warnings)
  target_precompile_headers(${donor} PRIVATE ${headers})
  foreach(target ${targets})
    target_precompile_headers(${target} REUSE_FROM ${donor})
  endforeach()
endforeach()
