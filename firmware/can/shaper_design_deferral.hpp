#pragma once
// Shaper designs off the real-time thread. A parameter change whose shaper
// design the node does not have (ShaperDesignCache) posts the design to the
// worker (ShaperDesignJob) and keeps the request; when the worker is done
// the designs go into the cache and the node handles the request again from
// the start, as if it arrived then: every check runs again on the state of
// that moment, the design is found and costs a copy, and the request is
// answered once. Nothing is applied before that (docs/safety.md
// "Real-time budget").
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <array>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "firmware/can/shaper_design_cache.hpp"
#include "firmware/can/storage_jobs.hpp"
#include "hal/axis.hpp"
#include "hal/can_port.hpp"
#include "hal/storage_worker.hpp"

namespace tnv::fw::can {

class ShaperDesignDeferral {
 public:
  explicit ShaperDesignDeferral(hal::StorageWorker* worker) noexcept : worker_(worker) {}
  ShaperDesignDeferral(const ShaperDesignDeferral&) = delete;
  ShaperDesignDeferral& operator=(const ShaperDesignDeferral&) = delete;

  // Without a worker nothing is deferred: the design runs in the request.
  bool can_defer() const noexcept { return worker_ != nullptr; }
  // A request is being handled (kept, in case it is deferred): not deferred yet.
  void begin_request(const hal::CanFrame& frame, MessageId id) noexcept {
    request_ = frame;
    request_id_ = id;
    deferred_ = false;
  }
  // The designs of `next`'s shapers marked `needed` go to the worker and the
  // request being handled waits for them: ok (deferred() then holds, and
  // the request must not be answered now), or busy when the worker refuses.
  ErrorCode defer(const std::array<bool, hal::kAxisCount>& needed, const NodeSettings& next) noexcept;
  bool deferred() const noexcept { return deferred_; }  // the request being handled waits
  bool pending() const noexcept { return pending_; }    // a job posted, its request not handled again
  bool job_done() const noexcept { return pending_ && worker_ != nullptr && worker_->done(); }

  // The job done: its designs go into `designs`; the request to handle again.
  struct Replay {
    hal::CanFrame frame{};
    MessageId id = MessageId::command;
  };
  Replay finish(ShaperDesignCache& designs) noexcept;

 private:
  hal::StorageWorker* worker_ = nullptr;
  // The request being handled, and the one waiting for its designs.
  hal::CanFrame request_{};
  MessageId request_id_ = MessageId::command;
  Replay waiting_{};
  bool pending_ = false;   // job_ posted, its request not yet handled again
  bool deferred_ = false;  // the request being handled was deferred: no answer now
  ShaperDesignJob job_{};
};

}  // namespace tnv::fw::can
