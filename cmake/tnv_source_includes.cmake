# tnv_source_includes(target PUBLIC|INTERFACE)
# Our headers are included by their path from the source root
# ("firmware/can/param_table.hpp"); installed, the same paths sit under
# <prefix>/include/tnv, so a consumer writes the same #include lines.
function(tnv_source_includes target scope)
  target_include_directories(${target} ${scope} $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                             $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/tnv>)
endfunction()
