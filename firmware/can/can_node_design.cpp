// CanNode: shaper designs off the real-time thread. A parameter change whose
// shaper design the node does not have (ShaperDesignCache) posts the design
// to the worker and keeps the request; when the worker is done the designs
// go into the cache and the request is handled again from the start, as if
// it arrived then: every check runs again on the state of that moment, the
// design is found and costs a copy, and the request is answered once.
// Nothing is applied before that (docs/safety.md "Real-time budget").
#include "firmware/can/can_node.hpp"

namespace tnv::fw::can {

ErrorCode CanNode::defer_for_designs(const std::array<bool, hal::kAxisCount>& needed, const NodeSettings& next) noexcept {
  std::array<ShaperSpec, hal::kAxisCount> specs{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) specs[i] = next.shaper[i].spec;
  design_job_.prepare(specs, needed);
  if (!storage_worker_->post(design_job_)) return ErrorCode::busy;
  design_pending_ = true;
  design_deferred_ = true;
  design_request_ = request_;
  design_request_id_ = request_id_;
  return ErrorCode::ok;
}

void CanNode::finish_design() noexcept {
  design_pending_ = false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (design_job_.designed(i)) designs_.insert(design_job_.spec(i), design_job_.design(i));
  // The request as it came: its tag names the host (ownership is checked again).
  access_.begin_request(design_request_.data[0], false);
  dispatch(design_request_, design_request_id_);
  // Handled again it finds its designs; should it defer once more (a host
  // changed its staged set meanwhile), it is answered after that job.
}

}  // namespace tnv::fw::can
