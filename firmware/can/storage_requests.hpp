#pragma once
// COMMAND save_params and load_params: the job posted to NodeStorage
// (carried out off the real-time thread when the node has a worker) and
// answered by one COMMAND_ACK in the service() that finds it done. While a
// job is in flight a second save/load, restore_defaults and every parameter
// change are busy: the job works on the set as it was, and the live set is
// never half-loaded. A loaded set goes through NodeParameters::apply(), the
// one path of change. Bounded work, no allocation, exceptions, locks or
// logging: it runs in CanNode::service().
#include "firmware/can/command_ack.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class StorageRequests {
 public:
  StorageRequests(const TickTask& task, HostAccess& access, CommandAck& ack, NodeStorage& storage,
                  NodeParameters& params) noexcept
      : task_(task), access_(access), ack_(ack), storage_(storage), params_(params) {}
  StorageRequests(const StorageRequests&) = delete;
  StorageRequests& operator=(const StorageRequests&) = delete;

  // ok when posted (answered later by finish()), else the refusal for the caller to answer now.
  ErrorCode begin(const hal::CanFrame& request, CommandCode code) noexcept;
  // The job is done (NodeStorage::job_done(), or run in begin() without a
  // worker): applies a loaded set and answers the request as it came.
  void finish() noexcept;

 private:
  const TickTask& task_;
  HostAccess& access_;
  CommandAck& ack_;
  NodeStorage& storage_;
  NodeParameters& params_;
};

}  // namespace tnv::fw::can
