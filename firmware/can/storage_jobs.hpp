#pragma once
// The node's two storage jobs, run off the real-time thread by a
// hal::StorageWorker (docs/safety.md "Storage off the real-time thread").
// prepare() runs in service() and is bounded (the image is encoded there,
// ~2.6 kB); run() runs on the worker and does the I/O; the node reads the
// result once the worker reports the job done. Each job owns its buffers,
// so the worker never touches the node's live settings.
#include <array>
#include <cstddef>
#include <cstdint>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_image.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/param_storage.hpp"
#include "hal/storage_worker.hpp"

namespace tnv::fw::can {

// save_params: the image of the settings at the request, written whole.
class SaveJob final : public hal::StorageJob {
 public:
  void prepare(hal::ParamStorage& storage, const NodeSettings& settings) noexcept;
  void run() noexcept override;
  ErrorCode result() const noexcept { return result_; }

 private:
  hal::ParamStorage* storage_ = nullptr;
  std::array<std::uint8_t, kParamImageMaxBytes> image_{};
  std::size_t size_ = 0;
  ErrorCode result_ = ErrorCode::ok;
};

// load_params: the current generation, else the previous one, decoded over
// a copy of the settings at the request (load_settings_with_fallback).
class LoadJob final : public hal::StorageJob {
 public:
  void prepare(hal::ParamStorage& current, hal::ParamStorage* previous, const NodeSettings& base) noexcept;
  void run() noexcept override;
  const LoadReport& report() const noexcept { return report_; }
  const NodeSettings& settings() const noexcept { return settings_; }

 private:
  hal::ParamStorage* current_ = nullptr;
  hal::ParamStorage* previous_ = nullptr;
  NodeSettings settings_{};
  LoadReport report_{};
};

}  // namespace tnv::fw::can
