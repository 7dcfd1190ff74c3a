#include "firmware/can/shaper_design_cache.hpp"

#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

namespace {

std::array<ShaperDesign, hal::kAxisCount> design_defaults() noexcept {
  const NodeSettings& d = cached_default_node_settings();
  std::array<ShaperDesign, hal::kAxisCount> out{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (validate(d.shaper[i].spec).ok) out[i] = design_shaper(d.shaper[i].spec, TickTask::kTickPeriodS);
  return out;
}

}  // namespace

const std::array<ShaperDesign, hal::kAxisCount>& cached_default_shaper_designs() noexcept {
  static const std::array<ShaperDesign, hal::kAxisCount> designs = design_defaults();
  return designs;
}

const ShaperDesign* ShaperDesignCache::find(const ShaperSpec& spec) const noexcept {
  const NodeSettings& d = cached_default_node_settings();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (same_spec(d.shaper[i].spec, spec) && validate(spec).ok) return &cached_default_shaper_designs()[i];
  for (const Entry& e : recent_)
    if (e.used && same_spec(e.spec, spec)) return &e.design;
  return nullptr;
}

void ShaperDesignCache::insert(const ShaperSpec& spec, const ShaperDesign& design) noexcept {
  Entry& e = recent_[next_];
  e.used = true;
  e.spec = spec;
  e.design = design;
  next_ = (next_ + 1) % recent_.size();
}

}  // namespace tnv::fw::can
