# cmake -DSOURCE_DIR=... -DOUT=... -DVERSION_NUMBER=... -P firmware_identity.cmake
# Writes the firmware's identity (firmware/can/firmware_identity.hpp) for
# this build: its version number and the commit it is built from. Run at
# every build; the file is rewritten only when its text changes, so an
# unchanged commit recompiles nothing.
set(build_id 0)
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} -C ${SOURCE_DIR} rev-parse --short=8 HEAD
                  OUTPUT_VARIABLE commit RESULT_VARIABLE failed OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(NOT failed AND commit MATCHES "^[0-9a-f]+$")
    set(build_id 0x${commit})
  endif()
endif()
set(text "// Generated at build time by cmake/firmware_identity.cmake: do not edit.
#include \"firmware/can/firmware_identity.hpp\"

namespace tnv::fw::can {
std::uint32_t firmware_version() noexcept { return ${VERSION_NUMBER}u; }
std::uint32_t firmware_build_id() noexcept { return ${build_id}u; }
}  // namespace tnv::fw::can
")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
