# The CMake package: `cmake --install <build> --prefix P --component dev`
# puts the host-side libraries, their headers and tnvConfig.cmake under P;
# a consumer then writes
#   find_package(tnv CONFIG REQUIRED)
#   target_link_libraries(app PRIVATE tnv::firmware)   # or tnv::tune, tnv::can_host, tnv::can_emu
# (docs/architecture.md "Using the libraries"; tests/package/ builds one).
include(CMakePackageConfigHelpers)

# The static libraries behind tnv::firmware, tnv::tune, tnv::can_host and
# tnv::can_emu, with the
# name each carries in the tnv:: namespace. tnv_warnings is only a link-
# time reference of the static libraries (their own -Werror flags are not
# passed on), but CMake needs it in the export set.
set(tnv_exported
  tnv_hal:hal tnv_work_meter:work_meter tnv_firmware:firmware tnv_warnings:build_warnings
  tnv_emulator:emulator tnv_driver_fpga:driver_fpga tnv_driver_emulated:driver_emulated
  tnv_driver_linux:driver_linux tnv_driver_socketcan:driver_socketcan tnv_driver_storage:driver_storage
  tnv_tune:tune tnv_gcode_lib:gcode tnv_score:score tnv_hil_lib:hil tnv_protogen_lib:protogen tnv_can_host:can_host
  tnv_can_emu:can_emu tnv_toml:toml tnv_toml_impl:toml_impl tnv_sqlite3:sqlite3 tnv_gpiod:gpiod)
set(tnv_export_targets "")
foreach(pair ${tnv_exported})
  string(REPLACE ":" ";" pair "${pair}")
  list(GET pair 0 target)
  list(GET pair 1 export_name)
  if(TARGET ${target})
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
    list(APPEND tnv_export_targets ${target})
  endif()
endforeach()

install(TARGETS ${tnv_export_targets} EXPORT tnvTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tnv)
# Headers keep their source-tree paths under include/tnv/.
foreach(dir hal firmware emulator drivers tools/tune tools/can tools/can_emu tools/hil tools/score tools/gcode tools/protogen)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tnv/${dir}
          COMPONENT dev FILES_MATCHING PATTERN "*.hpp")
endforeach()

set(tnv_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/tnv)
install(EXPORT tnvTargets NAMESPACE tnv:: DESTINATION ${tnv_cmake_dir} COMPONENT dev)
set(TNV_WITH_LIBGPIOD ${LIBGPIOD_FOUND})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/tnvConfig.cmake.in ${PROJECT_BINARY_DIR}/tnvConfig.cmake
                              INSTALL_DESTINATION ${tnv_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/tnvConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/tnvConfig.cmake ${PROJECT_BINARY_DIR}/tnvConfigVersion.cmake
        DESTINATION ${tnv_cmake_dir} COMPONENT dev)
