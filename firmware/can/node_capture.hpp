#pragma once
// On-target capture over CAN: CAPTURE_CONTROL (arm / abort / status /
// upload), the recorder fed once per tick, and the segmented upload,
// CAPTURE_DATA frames sent over as many service() calls as the transmit
// queue needs, only when nothing else waits (docs/can-protocol.md
// CAPTURE_CONTROL, CAPTURE_DATA). A capture armed for a motion records a running EXCITE, first
// tick to last.
//
// Size: holds the capture buffer (CaptureRecorder, kCaptureCapacityWords
// 32-bit words, 512 KiB), last of its members; the node holds it last too.
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <cstdint>

#include "firmware/can/capture_recorder.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

class NodeCapture {
 public:
  NodeCapture(std::uint8_t node_id, const TickTask& task, const HostAccess& access, NodeTransmit& tx) noexcept
      : node_id_(node_id), task_(task), access_(access), tx_(tx) {}
  NodeCapture(const NodeCapture&) = delete;
  NodeCapture& operator=(const NodeCapture&) = delete;

  // A new tick (settings: the live set): the sample, and the end of an EXCITE's capture.
  void on_tick(const NodeSettings& settings) noexcept;
  // CAPTURE_CONTROL of the request being handled, answered here (an
  // accepted upload by its data frames); `settings`: the live capture settings.
  void control(const hal::CanFrame& frame, const CaptureSettings& settings) noexcept;
  // CAPTURE_STATUS answering the request being handled.
  void reply(ErrorCode result) noexcept;
  // An EXCITE started: a capture armed for a motion records it, first tick to last.
  void excitation_started(const CaptureSettings& settings) noexcept;
  // The upload's next frames, while nothing else waits to be sent.
  void send_upload() noexcept;

  // Armed or recording: the capture settings may not change now.
  bool settings_locked() const noexcept;
  const CaptureRecorder& recorder() const noexcept { return capture_; }

 private:
  struct Upload {
    bool active = false;
    std::uint32_t offset_bytes = 0;
    std::uint16_t frames = 0;
    std::uint16_t next = 0;
  };

  std::uint8_t node_id_;
  const TickTask& task_;
  const HostAccess& access_;
  NodeTransmit& tx_;
  Upload upload_{};
  bool excite_capture_ = false;  // the capture records a running EXCITE: stop it when that ends
  CaptureRecorder capture_{};    // last: the big buffer
};

}  // namespace tnv::fw::can
