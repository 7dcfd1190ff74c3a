#pragma once
// The SocketCAN system-call interface lives with the Linux drivers (the
// firmware's CAN port uses it too); the host side names it here.
#include "drivers/linux/socket_api.hpp"
#include "tools/can/host_bus.hpp"

namespace tnv::can_host {

using drivers::linux_socket_api;
using drivers::SocketApi;
using drivers::SysResult;

}  // namespace tnv::can_host
