#pragma once
// A probe move (G38.2-G38.5): a line at its feed that watches the touch
// probe input and ends when it changes (docs/motion.md "Probe moves").
#include <cstdint>

namespace tnv::fw::motion {

// Which change ends the move, and whether reaching the end without it is an error.
enum class ProbeKind : std::uint8_t {
  none = 0,
  toward_or_error = 1,  // G38.2: until contact; no contact by the end is an error
  toward = 2,           // G38.3: until contact
  away_or_error = 3,    // G38.4: until contact is lost; still in contact at the end is an error
  away = 4,             // G38.5: until contact is lost
};

// The input state that ends (trips) a probe of this kind.
constexpr bool probe_trips_on(ProbeKind kind, bool touching) noexcept {
  const bool toward = kind == ProbeKind::toward_or_error || kind == ProbeKind::toward;
  return toward ? touching : !touching;
}
constexpr bool probe_end_is_error(ProbeKind kind) noexcept {
  return kind == ProbeKind::toward_or_error || kind == ProbeKind::away_or_error;
}

// How a probe move ended. The two errors stop the program (nothing after runs).
enum class ProbeOutcome : std::uint8_t {
  none = 0,
  tripped = 1,          // the input changed: braked to rest, the trip position latched
  not_tripped = 2,      // G38.3/G38.5 reached the end without a change: the program goes on
  failed = 3,           // G38.2/G38.4 reached the end without a change: an error
  already_tripped = 4,  // the input was already in the tripping state at the start: refused, an error
};

constexpr bool is_error(ProbeOutcome o) noexcept { return o == ProbeOutcome::failed || o == ProbeOutcome::already_tripped; }

constexpr const char* to_string(ProbeOutcome o) noexcept {
  switch (o) {
    case ProbeOutcome::none: return "none";
    case ProbeOutcome::tripped: return "tripped";
    case ProbeOutcome::not_tripped: return "not_tripped";
    case ProbeOutcome::failed: return "failed";
    case ProbeOutcome::already_tripped: return "already_tripped";
  }
  return "?";
}

}  // namespace tnv::fw::motion
