#pragma once
// The node's jobs run off the real-time thread by a
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
#include "firmware/shaper/shaper_design.hpp"
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

// Shaper designs for the specs a parameter change needs and the node does
// not have (ShaperDesignCache): designed here, on the worker, since a
// design costs more board time than a request may take.
class ShaperDesignJob final : public hal::StorageJob {
 public:
  // `needed[i]`: design specs[i]; run() skips a spec that fails validate().
  void prepare(const std::array<ShaperSpec, hal::kAxisCount>& specs, const std::array<bool, hal::kAxisCount>& needed) noexcept;
  void run() noexcept override;
  bool designed(std::size_t axis) const noexcept { return designed_[axis]; }
  const ShaperSpec& spec(std::size_t axis) const noexcept { return specs_[axis]; }
  const ShaperDesign& design(std::size_t axis) const noexcept { return designs_[axis]; }

 private:
  std::array<ShaperSpec, hal::kAxisCount> specs_{};
  std::array<bool, hal::kAxisCount> needed_{};
  std::array<bool, hal::kAxisCount> designed_{};
  std::array<ShaperDesign, hal::kAxisCount> designs_{};
};

// load_params: the current generation, else the previous one, decoded over
// a copy of the settings at the request (load_settings_with_fallback); the
// loaded set's shapers designed as well, so applying it needs no design.
class LoadJob final : public hal::StorageJob {
 public:
  void prepare(hal::ParamStorage& current, hal::ParamStorage* previous, const NodeSettings& base) noexcept;
  void run() noexcept override;
  const LoadReport& report() const noexcept { return report_; }
  const NodeSettings& settings() const noexcept { return settings_; }
  const ShaperDesignJob& designs() const noexcept { return designs_; }

 private:
  hal::ParamStorage* current_ = nullptr;
  hal::ParamStorage* previous_ = nullptr;
  NodeSettings settings_{};
  LoadReport report_{};
  ShaperDesignJob designs_{};
};

}  // namespace tnv::fw::can
