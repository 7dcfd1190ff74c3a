// NodeStorage: save_params and load_params, posted to the worker and
// finished in the service() that finds them done.
#include "firmware/can/node_storage.hpp"

namespace tnv::fw::can {

ErrorCode NodeStorage::begin(const hal::CanFrame& request, CommandCode code, const NodeSettings& settings) noexcept {
  hal::StorageJob* job = nullptr;
  if (code == CommandCode::save_params) {
    save_job_.prepare(current_, settings);
    job = &save_job_;
  } else {
    load_job_.prepare(current_, previous_, settings);
    job = &load_job_;
  }
  if (worker_ == nullptr) {
    job->run();  // no worker: in this service(), as a node without one must
  } else if (!worker_->post(*job)) {
    return ErrorCode::busy;
  }
  pending_ = true;
  code_ = code;
  request_ = request;
  return ErrorCode::ok;
}

NodeStorage::Finished NodeStorage::finish() noexcept {
  pending_ = false;
  Finished done;
  done.code = code_;
  done.tag = request_.dlc > 0 ? request_.data[0] : 0;
  if (code_ == CommandCode::save_params) {
    // Nothing could change the set while the job ran (the node refused every change): it is what was saved.
    done.result = save_job_.result();
    fault_ = done.result != ErrorCode::ok;
    if (done.result == ErrorCode::ok) unsaved_ = false;
    return done;
  }
  // The current image, else the previous generation (still reported as a
  // storage fault), else nothing changes.
  const LoadReport& loaded = load_job_.report();
  if (loaded.source == LoadSource::nothing_stored) {
    done.result = ErrorCode::not_ready;
  } else if (loaded.source == LoadSource::neither) {
    fault_ = true;
    done.result = loaded.result();
  } else {
    done.loaded = &load_job_;
  }
  return done;
}

void NodeStorage::loaded_applied() noexcept {
  const bool previous = load_job_.report().fault();
  unsaved_ = previous;  // the previous set is not what was last saved
  fault_ = previous;
}

}  // namespace tnv::fw::can
