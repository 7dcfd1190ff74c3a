#pragma once
// The on-target capture as a host runs it: configure (channels, trigger,
// decimation) and arm; after the motion, optionally keep recording a while
// and stop; wait for the recording, upload it with gap recovery and decode
// it into named columns.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "tools/can/capture_table.hpp"
#include "tools/can/node_client.hpp"

namespace tnv::can_host {

struct CaptureSetup {
  std::string channels;  // "" = what the node has; else parse_channel_list()'s form
  std::string trigger;   // "" = what the node has; immediate | motion | fault
  int decimation = 0;    // 0 = what the node has; else 1..255 ticks per sample
};

// The recording could not be waited for or decoded.
class CaptureError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

const char* capture_state_name(can::CaptureState s);

// Checks the setup before anything is sent: throws std::invalid_argument
// naming what is wrong.
void check_capture_setup(const CaptureSetup& setup);

// The node's channel mask (capture.channels and capture.channels_high).
can::ChannelMask read_channel_mask(NodeClient& client);
// Stages `mask` as capture.channels and capture.channels_high (the caller commits).
void stage_channel_mask(NodeClient& client, can::ChannelMask mask);

struct ArmedCapture {
  can::ChannelMask channel_mask = 0;
  std::string trigger;  // as the node has it now
  int decimation = 1;
  CaptureStatus status;
};

// Commits the setup's changes as one set (if any), then arms.
ArmedCapture arm_capture(NodeClient& client, const CaptureSetup& setup);

// Keeps receiving for `tail`, then stops the recording if it is still going
// (it keeps what it has).
void stop_capture_after(NodeClient& client, Micros tail);

struct DownloadedCapture {
  CaptureTable table;
  CaptureStatus status;
  can::ChannelMask channel_mask = 0;
  std::size_t bytes = 0;
  double upload_s = 0.0;  // on the bus clock
  std::uint64_t rerequests = 0;
};

// Waits up to `wait` for the recording to be done (0: it must be done
// already), uploads and decodes it. Throws CaptureError, RequestError, BusError.
DownloadedCapture download_capture(NodeClient& client, Micros wait, const UploadProgress& progress = {});

}  // namespace tnv::can_host
