# Three libraries our code links, as one target each: tnv_toml (toml++),
# tnv_sqlite3, tnv_gpiod. By default they are Debian's shared libraries.
# With TNV_STATIC_TOOLS (the `campaign` preset) tnv-hil carries them inside,
# and libstdc++ and libgcc too: a campaign worker starts tens of thousands
# of short processes, and each one's dynamic loader then maps and binds
# libc and libm only, not eight libraries (docs/performance.md "A campaign
# worker's build"). SQLite and libgpiod come from the static archives
# their -dev packages ship; Debian ships toml++ as headers and a shared
# library only, so its implementation is compiled here, once
# (cmake/toml_impl.cpp).
option(TNV_STATIC_TOOLS "Link tnv-hil with toml++, SQLite, libgpiod, libstdc++ and libgcc inside (campaign workers)" OFF)

add_library(tnv_toml INTERFACE)
if(TNV_STATIC_TOOLS)
  get_target_property(tnv_toml_includes tomlplusplus::tomlplusplus INTERFACE_INCLUDE_DIRECTORIES)
  add_library(tnv_toml_impl STATIC ${CMAKE_CURRENT_LIST_DIR}/toml_impl.cpp)
  target_include_directories(tnv_toml_impl SYSTEM PUBLIC ${tnv_toml_includes})
  # The library's own build of toml++ (not header-only: one copy of its code).
  target_compile_definitions(tnv_toml_impl PUBLIC TOML_HEADER_ONLY=0)
  target_link_libraries(tnv_toml INTERFACE tnv_toml_impl)
else()
  target_link_libraries(tnv_toml INTERFACE tomlplusplus::tomlplusplus)
endif()

# `target` links Debian's shared library `imported`, or with
# TNV_STATIC_TOOLS the static archive lib<archive>.a its -dev package ships
# beside it (and ARGN, what that archive needs after it).
function(tnv_debian_library target imported archive)
  if(NOT TNV_STATIC_TOOLS)
    target_link_libraries(${target} INTERFACE ${imported})
    return()
  endif()
  find_library(TNV_${archive}_ARCHIVE NAMES lib${archive}.a)
  if(NOT TNV_${archive}_ARCHIVE)
    message(FATAL_ERROR "TNV_STATIC_TOOLS: lib${archive}.a not found (Debian's lib${archive}-dev ships it)")
  endif()
  get_target_property(includes ${imported} INTERFACE_INCLUDE_DIRECTORIES)
  if(includes)
    target_include_directories(${target} SYSTEM INTERFACE ${includes})
  endif()
  target_link_libraries(${target} INTERFACE ${TNV_${archive}_ARCHIVE} ${ARGN})
endfunction()

add_library(tnv_sqlite3 INTERFACE)
if(SQLite3_FOUND)
  tnv_debian_library(tnv_sqlite3 SQLite::SQLite3 sqlite3 m ${CMAKE_DL_LIBS} Threads::Threads)
endif()
add_library(tnv_gpiod INTERFACE)
if(LIBGPIOD_FOUND)
  tnv_debian_library(tnv_gpiod PkgConfig::LIBGPIOD gpiod)
endif()

# libstdc++ and libgcc inside tnv-hil (tools/CMakeLists.txt): with the three
# above static, nothing else it links loads them. (tnvctl's page server
# links more shared libraries; it is no campaign worker.)
function(tnv_static_runtime target)
  if(TNV_STATIC_TOOLS)
    target_link_options(${target} PRIVATE -static-libstdc++ -static-libgcc)
  endif()
endfunction()
