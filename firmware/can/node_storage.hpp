#pragma once
// The CAN node's parameter storage: COMMAND save_params and load_params
// off the real-time thread, and what the heartbeat says about them
// (storage fault, parameters unsaved). A request's job is prepared in
// service() (bounded: the image encode, a copy of the settings), posted to
// the hal::StorageWorker (without one, unit tests: run at once), and the
// request is answered in the service() that finds the job done
// (storage_jobs.hpp, docs/safety.md "Storage off the real-time thread").
// A load falls back to the previous generation (param_fallback.hpp) and
// hands the loaded set to the node, which applies it like any change.
//
// One job at a time; the node refuses a second one, and every parameter
// change, while one is pending: the job works on the set as it was.
// Bounded work, no allocation, exceptions, locks or logging in service().
#include <cstdint>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/storage_jobs.hpp"
#include "hal/can_port.hpp"
#include "hal/param_storage.hpp"
#include "hal/storage_worker.hpp"

namespace tnv::fw::can {

class NodeStorage {
 public:
  // `fault`: the start-up load failed (reported until a save or load succeeds).
  NodeStorage(hal::ParamStorage& current, hal::ParamStorage* previous, hal::StorageWorker* worker,
              bool fault) noexcept
      : current_(current), previous_(previous), worker_(worker), fault_(fault) {}
  NodeStorage(const NodeStorage&) = delete;
  NodeStorage& operator=(const NodeStorage&) = delete;

  // save_params / load_params (`code`) asked by `request`, over `settings`:
  // ok when the job is posted, or run at once without a worker (then it is
  // done: finish() it now); busy when the worker refuses it.
  ErrorCode begin(const hal::CanFrame& request, CommandCode code, const NodeSettings& settings) noexcept;
  bool pending() const noexcept { return pending_; }  // posted, not answered yet
  bool has_worker() const noexcept { return worker_ != nullptr; }
  bool job_done() const noexcept { return pending_ && worker_ != nullptr && worker_->done(); }

  // The pending job, done: no longer pending. A save's outcome is final; a
  // load with a set to apply hands it over in `loaded` (result ok), and the
  // node calls loaded_applied() if it applied it.
  struct Finished {
    CommandCode code = CommandCode::save_params;
    std::uint8_t tag = 0;              // the request's tag, echoed by its COMMAND_ACK
    ErrorCode result = ErrorCode::ok;
    const LoadJob* loaded = nullptr;   // the set (and its shaper designs) to apply
  };
  Finished finish() noexcept;
  void loaded_applied() noexcept;

  bool fault() const noexcept { return fault_; }
  bool unsaved() const noexcept { return unsaved_; }
  void changed() noexcept { unsaved_ = true; }  // the live set differs from what is saved

 private:
  hal::ParamStorage& current_;
  hal::ParamStorage* previous_ = nullptr;   // the generation before (param_fallback.hpp)
  hal::StorageWorker* worker_ = nullptr;
  // The request in flight: the frame as it came (the deferred COMMAND_ACK
  // answers it), and the job the worker runs.
  CommandCode code_ = CommandCode::save_params;
  bool pending_ = false;
  hal::CanFrame request_{};
  SaveJob save_job_{};
  LoadJob load_job_{};
  bool fault_ = false;
  bool unsaved_ = false;
};

}  // namespace tnv::fw::can
