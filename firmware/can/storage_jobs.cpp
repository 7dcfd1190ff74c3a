#include "firmware/can/storage_jobs.hpp"

#include <span>

#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

void SaveJob::prepare(hal::ParamStorage& storage, const NodeSettings& settings) noexcept {
  storage_ = &storage;
  size_ = encode_image(settings, image_);
  result_ = ErrorCode::ok;
}

void SaveJob::run() noexcept {
  if (storage_ == nullptr || size_ == 0) {
    result_ = ErrorCode::storage_error;
    return;
  }
  // The generation is read here, on the worker: it needs the stored image.
  stamp_generation(std::span<std::uint8_t>(image_.data(), size_), next_generation(*storage_));
  result_ = storage_->write(std::span<const std::uint8_t>(image_.data(), size_)) == hal::HalStatus::ok
                ? ErrorCode::ok
                : ErrorCode::storage_error;
}

void LoadJob::prepare(hal::ParamStorage& current, hal::ParamStorage* previous, const NodeSettings& base) noexcept {
  current_ = &current;
  previous_ = previous;
  settings_ = base;
  report_ = {};
  designs_.prepare({}, {});
}

void LoadJob::run() noexcept {
  if (current_ == nullptr) {
    report_.source = LoadSource::neither;
    report_.current = ErrorCode::storage_error;
    return;
  }
  report_ = load_settings_with_fallback(*current_, previous_, settings_);
  // Every axis' spec; run() designs the valid ones (an invalid set is refused whole when applied).
  std::array<ShaperSpec, hal::kAxisCount> specs{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) specs[i] = settings_.shaper[i].spec;
  std::array<bool, hal::kAxisCount> all{};
  all.fill(true);
  designs_.prepare(specs, all);
  designs_.run();
}

void ShaperDesignJob::prepare(const std::array<ShaperSpec, hal::kAxisCount>& specs,
                              const std::array<bool, hal::kAxisCount>& needed) noexcept {
  specs_ = specs;
  needed_ = needed;
  designed_ = {};
}

void ShaperDesignJob::run() noexcept {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    designed_[i] = needed_[i] && validate(specs_[i]).ok;
    if (designed_[i]) designs_[i] = design_shaper(specs_[i], TickTask::kTickPeriodS);
  }
}

}  // namespace tnv::fw::can
