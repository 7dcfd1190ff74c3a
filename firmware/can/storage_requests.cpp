// StorageRequests: COMMAND save_params / load_params (storage_requests.hpp).
#include "firmware/can/storage_requests.hpp"

#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

ErrorCode StorageRequests::begin(const hal::CanFrame& request, CommandCode code) noexcept {
  if (task_.moving() || params_.worker_busy()) return ErrorCode::busy;
  const ErrorCode e = storage_.begin(request, code, params_.settings());
  if (e == ErrorCode::ok && !storage_.has_worker()) finish();  // run in this service(): answered now
  return e;
}

void StorageRequests::finish() noexcept {
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

}  // namespace tnv::fw::can
