#pragma once
// The pending parameter set of PARAM_REQUEST stage / commit / discard:
// (id, value) pairs, each already range-checked, at most one per id (a
// second stage of the same id overwrites). Nothing here touches the live
// settings until the node commits.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/can/node_settings.hpp"

namespace tnv::fw::can {

struct StagedParam {
  std::uint16_t id = 0;
  double value = 0.0;
};

class StagedParams {
 public:
  static constexpr std::size_t kCapacity = 384;  // > the table's parameters (tested; 305 with X, Y, Z)

  // Adds or overwrites; false (nothing changes) when full.
  bool put(std::uint16_t id, double value) noexcept;
  void clear() noexcept { size_ = 0; }
  std::size_t size() const noexcept { return size_; }
  bool empty() const noexcept { return size_ == 0; }
  std::span<const StagedParam> items() const noexcept { return {items_.data(), size_}; }
  // Writes every staged value into `settings` (ids are known: checked at stage).
  void write_into(NodeSettings& settings) const noexcept;

 private:
  std::array<StagedParam, kCapacity> items_{};
  std::size_t size_ = 0;
};

}  // namespace tnv::fw::can
