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
# The firmware has its own (Eigen alone; no exceptions, the work meter's
# coverage). The host tools' libraries and programs share one, built once
# in an object library and reused (REUSE_FROM), as the test suites share
# theirs: one parse instead of one per target (about 4 CPU-s each). GCC
# takes a header only from a compile with the same code-generation flags,
# so the libraries the Python module links (position-independent, see
# tools/python/CMakeLists.txt) share a second one built like them; with
# -Winvalid-pch and -Werror a mismatch stops the build.
if(TARGET tnv_firmware)
  target_precompile_headers(tnv_firmware PRIVATE <Eigen/Dense>)
endif()
set(tnv_tools_precompiled tnv-hil tnvctl tnv_cli tnv_freq_response_cli tnv_hil_lib tnv_can_host tnv_can_emu tnv_fw_lib
                          tnv_protogen_lib tnv_score tnv_serve tnv_tune tnv_campaign)
foreach(target ${tnv_tools_precompiled})
  if(NOT TARGET ${target})  # not in this configuration (no cpp-httplib, no tests)
    continue()
  endif()
  get_target_property(pic ${target} POSITION_INDEPENDENT_CODE)
  set(donor tnv_tools_pch)
  if(pic)
    set(donor tnv_tools_pch_pic)
  endif()
  if(NOT TARGET ${donor})
    add_library(${donor} OBJECT ${CMAKE_CURRENT_LIST_DIR}/tools_pch.cpp)
    target_link_libraries(${donor} PRIVATE CLI11::CLI11 nlohmann_json::nlohmann_json Eigen3::Eigen tnv_warnings)
    target_precompile_headers(${donor} PRIVATE <CLI/CLI.hpp> <nlohmann/json.hpp> <Eigen/Dense>)
    # The options tools/ compiles with (the fuzz build's coverage among them).
    get_directory_property(tools_options DIRECTORY ${PROJECT_SOURCE_DIR}/tools COMPILE_OPTIONS)
    target_compile_options(${donor} PRIVATE ${tools_options})
    if(pic)
      set_target_properties(${donor} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      target_compile_options(${donor} PRIVATE -fno-semantic-interposition)
    endif()
  endif()
  target_precompile_headers(${target} REUSE_FROM ${donor})
endforeach()
