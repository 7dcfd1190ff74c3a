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

# The static archive Debian's -dev package puts beside the shared library.
function(tnv_static_archive out name)
  find_library(${out} NAMES lib${name}.a)
  if(NOT ${out})
    message(FATAL_ERROR "TNV_STATIC_TOOLS: lib${name}.a not found (Debian's lib${name}-dev ships it)")
  endif()
endfunction()

add_library(tnv_sqlite3 INTERFACE)
if(SQLite3_FOUND)
  if(TNV_STATIC_TOOLS)
    tnv_static_archive(TNV_SQLITE3_ARCHIVE sqlite3)
    target_include_directories(tnv_sqlite3 SYSTEM INTERFACE ${SQLite3_INCLUDE_DIRS})
    target_link_libraries(tnv_sqlite3 INTERFACE ${TNV_SQLITE3_ARCHIVE} m ${CMAKE_DL_LIBS} Threads::Threads)
  else()
    target_link_libraries(tnv_sqlite3 INTERFACE SQLite::SQLite3)
  endif()
endif()

add_library(tnv_gpiod INTERFACE)
if(LIBGPIOD_FOUND)
  if(TNV_STATIC_TOOLS)
    tnv_static_archive(TNV_GPIOD_ARCHIVE gpiod)
    target_include_directories(tnv_gpiod SYSTEM INTERFACE ${LIBGPIOD_INCLUDE_DIRS})
    target_link_libraries(tnv_gpiod INTERFACE ${TNV_GPIOD_ARCHIVE})
  else()
    target_link_libraries(tnv_gpiod INTERFACE PkgConfig::LIBGPIOD)
  endif()
endif()

# libstdc++ and libgcc inside tnv-hil (tools/CMakeLists.txt): with the three
# above static, nothing else it links loads them. (tnvctl's page server
# links more shared libraries; it is no campaign worker.)
function(tnv_static_runtime target)
  if(TNV_STATIC_TOOLS)
    target_link_options(${target} PRIVATE -static-libstdc++ -static-libgcc)
  endif()
endfunction()
