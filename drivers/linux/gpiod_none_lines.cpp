// Built without libgpiod: no line can be opened.
#include "drivers/linux/gpio_lines.hpp"

namespace tnv::drivers {

std::unique_ptr<BoardLines> open_board_lines(const LineConfig& config, std::string& error) {
  if (!config.any()) return nullptr;
  error = "GPIO lines are configured but this build has no libgpiod (install libgpiod-dev and rebuild)";
  return nullptr;
}

const char* gpio_backend() noexcept { return ""; }

}  // namespace tnv::drivers
