// CanNode: the worker's jobs. save_params and load_params, carried out off the real-time
// thread by NodeStorage (node_storage.hpp) and answered by one COMMAND_ACK
// in the service() that finds the job done. While a job is in flight a
// second save/load, restore_defaults and every parameter change are busy:
// the job works on the set as it was, and the live set is never half-loaded.
// And a request deferred for its shaper designs (shaper_design_deferral.hpp),
// handled again when the worker has made them.
#include "firmware/can/can_node.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

ErrorCode CanNode::begin_storage(const hal::CanFrame& request, CommandCode code) noexcept {
  if (moving() || worker_busy()) return ErrorCode::busy;
  const ErrorCode e = storage_.begin(request, code, params_.settings());
  if (e == ErrorCode::ok && !storage_.has_worker()) finish_storage();  // run in this service(): answered now
  return e;
}

void CanNode::collect_worker() noexcept {
  // One job at a time (worker_busy() refuses a second): the one done is the one pending.
  if (storage_.pending()) {
    if (storage_.job_done()) finish_storage();
    return;
  }
  if (design_.job_done()) finish_design();
}

void CanNode::finish_storage() noexcept {
  const NodeStorage::Finished done = storage_.finish();
  ErrorCode e = done.result;
  if (done.loaded != nullptr) {
    // The job designed the loaded shapers: applying them costs a copy.
    const ShaperDesignJob& made = done.loaded->designs();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      if (made.designed(i)) params_.designs().insert(made.spec(i), made.design(i));
    // The machine may have started moving since the request: then busy, nothing applied.
    e = params_.apply(done.loaded->settings(), true, false);
    if (e == ErrorCode::ok) storage_.loaded_applied();
  }
  // The reply answers the request as it came, echoing its tag.
  access_.answer_as(done.tag);
  ack_.send(kCommandMsg.id, static_cast<std::uint8_t>(done.code), e, 0);
}

void CanNode::finish_design() noexcept {
  const ShaperDesignDeferral::Replay replay = design_.finish(params_.designs());
  // The request as it came: its tag names the host (ownership is checked again).
  access_.begin_request(replay.frame.data[0], false);
  dispatch(replay.frame, replay.id);
  // Handled again it finds its designs; should it defer once more (a host
  // changed its staged set meanwhile), it is answered after that job.
}

}  // namespace tnv::fw::can
