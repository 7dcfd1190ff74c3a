// tnv::firmware alone: the parameter table, looked up by name.
#include <cstdio>

#include "firmware/can/param_table.hpp"

int main() {
  const auto* gamma = tnv::fw::can::find_param("x.sliding.gamma");
  if (gamma == nullptr) {
    std::puts("x.sliding.gamma: not in the parameter table");
    return 1;
  }
  std::printf("params %zu, x.sliding.gamma id %u\n", tnv::fw::can::param_table().size(), unsigned{gamma->id});
  return 0;
}
