#pragma once
// What firmware a node runs, as it reports it (sys.firmware_version,
// sys.build_id): defined in a source the build generates
// (cmake/firmware_identity.cmake).
#include <cstdint>

namespace tnv::fw::can {

// major * 10000 + minor * 100 + patch (0.1.0 reads 100).
std::uint32_t firmware_version() noexcept;
// The first 32 bits of the git commit the firmware was built from; 0 when
// it was not built from a git checkout. Local changes on top of the commit
// do not change it.
std::uint32_t firmware_build_id() noexcept;

}  // namespace tnv::fw::can
