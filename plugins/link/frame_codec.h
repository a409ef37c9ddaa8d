// SPDX-License-Identifier: GPL-3.0-or-later
// The link protocol's bytes, without any I/O (docs/protocol.md, arduino-lib/src/
// unimouse_protocol.h). The decoder takes the firmware's bytes as they come, in pieces of any
// size: partial frames wait for the rest, unknown ids are counted and skipped one byte at a time,
// so garbage never stops it.
#ifndef UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_
#define UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "unimouse_protocol.h"

namespace unimouse::link {

/// One complete frame from the firmware.
struct FirmwareFrame {
  uint8_t id = 0;
  int value = 0;              ///< motor command (clamped), manager code, or 0
  std::string text;           ///< log line, or a debug value's name
  float number = 0;           ///< debug value
  std::vector<uint8_t> data;  ///< debug walls (x, y, walls, known), visited (x, y), path (x, y...)
};

class FrameDecoder {
 public:
  /// Consumes `bytes`, appending every frame they complete to `out`.
  void Feed(std::span<const uint8_t> bytes, std::vector<FirmwareFrame>& out);

  uint64_t frames() const { return frames_; }
  uint64_t unknown_bytes() const { return unknown_bytes_; }
  /// Ids seen that the protocol does not define for this direction, each once, in order.
  const std::vector<uint8_t>& unknown_ids() const { return unknown_ids_; }
  /// Throws away a partial frame, as after a reconnection.
  void Reset() {
    pending_.clear();
    skipping_log_ = false;
  }

 private:
  // bytes of the frame being assembled, its id first
  std::vector<uint8_t> pending_;
  bool skipping_log_ = false;  // inside an overlong log line, until its 0x00
  uint64_t frames_ = 0;
  uint64_t unknown_bytes_ = 0;
  std::vector<uint8_t> unknown_ids_;
};

/// Appends a 2-byte sensor frame.
void PutSensorFrame(uint8_t id, uint16_t value, std::string& out);
/// Appends a ToF frame for a reading in metres (full scale: no target).
void PutTofFrame(uint8_t id, double distance_m, double full_scale_m, std::string& out);
/// Appends an encoder frame; counts beyond int16 are clamped.
void PutEncoderFrame(uint8_t id, long counts, std::string& out);
/// Appends a clock frame: sim time in microseconds, modulo 2^32.
void PutClockFrame(uint64_t time_us, std::string& out);

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_
