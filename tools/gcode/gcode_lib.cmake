# The G-code library (tools/gcode): included by tools/CMakeLists.txt and by
# the fuzz build (-DTNV_FUZZ=ON), which has no tools/ but fuzzes the
# interpreter (gcode_canon). Files are read as the daemon reads its own
# (drivers/storage/regular_file.hpp): no emulator (layering.gcode_links).
file(GLOB TNV_GCODE_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tools/gcode/*.cpp)
add_library(tnv_gcode_lib STATIC ${TNV_GCODE_SOURCES})
tnv_source_includes(tnv_gcode_lib PUBLIC)
target_link_libraries(tnv_gcode_lib PUBLIC tnv_firmware PRIVATE tnv_driver_storage tnv_warnings)
