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
list(LENGTH tnv_precompiled n)
math(EXPR last "${n} - 1")
foreach(i RANGE 0 ${last} 2)
  math(EXPR j "${i} + 1")
  list(GET tnv_precompiled ${i} target)
  list(GET tnv_precompiled ${j} headers)
  # A target that this configuration does not build (no cpp-httplib, no tests) is skipped.
  if(TARGET ${target})
    target_precompile_headers(${target} PRIVATE ${${headers}})
  endif()
endforeach()
