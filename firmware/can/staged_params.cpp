#include "firmware/can/staged_params.hpp"

#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {

bool StagedParams::put(std::uint16_t id, double value) noexcept {
  for (std::size_t i = 0; i < size_; ++i) {
    if (items_[i].id == id) {
      items_[i].value = value;
      return true;
    }
  }
  if (size_ == kCapacity) return false;
  items_[size_++] = {id, value};
  return true;
}

void StagedParams::write_into(NodeSettings& settings) const noexcept {
  for (const StagedParam& s : items()) {
    const ParamDef* p = find_param(s.id);
    if (p != nullptr && p->set != nullptr) p->set(settings, s.value);
  }
}

}  // namespace tnv::fw::can
