// CanNode: save_params and load_params off the real-time thread. The
// request is checked and its job prepared in service() (bounded: the image
// encode, a copy of the settings), posted to the hal::StorageWorker, and
// answered by one COMMAND_ACK in the service() that finds the job done.
// While a job is in flight a second save/load, restore_defaults and every
// parameter change are busy: the job works on the set as it was, and the
// live set is never half-loaded.
#include "firmware/can/can_node.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

ErrorCode CanNode::begin_storage(const hal::CanFrame& request, CommandCode code) noexcept {
  if (moving() || worker_busy()) return ErrorCode::busy;
  hal::StorageJob* job = nullptr;
  if (code == CommandCode::save_params) {
    save_job_.prepare(storage_, settings_);
    job = &save_job_;
  } else {
    load_job_.prepare(storage_, previous_storage_, settings_);
    job = &load_job_;
  }
  if (storage_worker_ == nullptr) {
    job->run();  // no worker: in this service(), as a node without one must
  } else if (!storage_worker_->post(*job)) {
    return ErrorCode::busy;
  }
  storage_pending_ = true;
  storage_code_ = code;
  storage_request_ = request;
  if (storage_worker_ == nullptr) finish_storage();
  return ErrorCode::ok;
}

void CanNode::collect_worker() noexcept {
  // One job at a time (worker_busy() refuses a second): the one done is the one pending.
  if (!worker_busy() || storage_worker_ == nullptr || !storage_worker_->done()) return;
  if (storage_pending_)
    finish_storage();
  else
    finish_design();
}

void CanNode::finish_storage() noexcept {
  storage_pending_ = false;
  const ErrorCode e = storage_code_ == CommandCode::save_params ? finish_save() : finish_load();
  // The reply answers the request kept in storage_request_, echoing its tag.
  access_.answer_as(storage_request_.dlc > 0 ? storage_request_.data[0] : 0);
  reply_ack(kCommandMsg.id, static_cast<std::uint8_t>(storage_code_), e, 0);
}

ErrorCode CanNode::finish_save() noexcept {
  // Nothing could change the set while the job ran (apply_settings was busy): it is what was saved.
  const ErrorCode e = save_job_.result();
  storage_fault_ = e != ErrorCode::ok;
  if (e == ErrorCode::ok) unsaved_ = false;
  return e;
}

ErrorCode CanNode::finish_load() noexcept {
  // The current image, else the previous generation (still reported as a
  // storage fault), else nothing changes.
  const LoadReport& loaded = load_job_.report();
  if (loaded.source == LoadSource::nothing_stored) return ErrorCode::not_ready;
  if (loaded.source == LoadSource::neither) {
    storage_fault_ = true;
    return loaded.result();
  }
  // The job designed the loaded shapers: applying them costs a copy.
  const ShaperDesignJob& made = load_job_.designs();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (made.designed(i)) designs_.insert(made.spec(i), made.design(i));
  // The machine may have started moving since the request: then busy, nothing applied.
  const ErrorCode e = apply_settings(load_job_.settings(), true, false);
  if (e == ErrorCode::ok) {
    unsaved_ = loaded.fault();  // the previous set is not what was last saved
    storage_fault_ = loaded.fault();
  }
  return e;
}

}  // namespace tnv::fw::can
