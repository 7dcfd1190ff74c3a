#pragma once

namespace tnv::hal {

// Hardware watchdog: if not kicked in time the board zeroes the DACs and
// drops the enables on its own.
class Watchdog {
 public:
  virtual ~Watchdog() = default;
  virtual void kick() noexcept = 0;
};

}  // namespace tnv::hal
