#pragma once
// tnv-fw --check-config --probe: opens what the config names, one device
// at a time, and closes it again: the board's spidev (mode and speed set,
// as at the start), each configured GPIO line (requested as the daemon
// requests it: outputs inactive), and the CAN interface (a raw socket bound
// to it). The Unix-socket cases (board.transport = "socket", a "unix:" CAN
// path) belong to the bench rig and are listed as not probed. Nothing is
// written to the board.
#include <string>
#include <vector>

#include "tools/tnv-fw/fw_config.hpp"

namespace tnv::fwd {

struct ProbeItem {
  std::string what;    // "board.path /dev/spidev0.0", "lines.estop TNV_ESTOP", "can.interface can0"
  bool ok = false;
  bool probed = true;  // false: not a device (socket transports), listed only
  std::string detail;  // the error when !ok, or why it was not probed
};

struct ProbeReport {
  std::vector<ProbeItem> items;
  bool ok() const noexcept;
  std::size_t failures() const noexcept;
};

ProbeReport probe_devices(const DaemonConfig& config);

}  // namespace tnv::fwd
