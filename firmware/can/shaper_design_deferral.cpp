// ShaperDesignDeferral: a request waiting for the shaper designs it needs.
#include "firmware/can/shaper_design_deferral.hpp"

namespace tnv::fw::can {

ErrorCode ShaperDesignDeferral::defer(const std::array<bool, hal::kAxisCount>& needed, const NodeSettings& next) noexcept {
  std::array<ShaperSpec, hal::kAxisCount> specs{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) specs[i] = next.shaper[i].spec;
  job_.prepare(specs, needed);
  if (worker_ == nullptr || !worker_->post(job_)) return ErrorCode::busy;
  pending_ = true;
  deferred_ = true;
  waiting_ = {request_, request_id_};
  return ErrorCode::ok;
}

ShaperDesignDeferral::Replay ShaperDesignDeferral::finish(ShaperDesignCache& designs) noexcept {
  pending_ = false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (job_.designed(i)) designs.insert(job_.spec(i), job_.design(i));
  return waiting_;
}

}  // namespace tnv::fw::can
