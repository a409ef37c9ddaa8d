// SPDX-License-Identifier: GPL-3.0-or-later
// The link protocol's bytes, without any I/O (docs/protocol.md, arduino-lib/src/
// unimouse_protocol.h). The decoder takes the firmware's bytes as they come, in pieces of any
// size: partial frames wait for the rest, unknown ids are counted and skipped one byte at a time,
// so garbage never stops it. Printable text between frames (a board's Serial.print) is read as
// lines of the firmware's log. Which data frames there are (sensor readings out, commands in) is
// the link's frame table; the control frames (manager, log, clock, debug) are the protocol's own.
#ifndef UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_
#define UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "unimouse/component.h"
#include "unimouse_protocol.h"

namespace unimouse::link {

/// How a data frame carries one signal's value.
enum class Encoding {
  kTof,    ///< uint16 counts of the ToF full scale; 0xFFFF at or beyond it
  kI16,    ///< int16, rounded and clamped
  kF32,    ///< IEEE 754 single precision
  kMotor,  ///< int16 H-bridge command, clamped to +-UNIMOUSE_MOTOR_MAX
};

/// Returns the payload bytes of a frame in `encoding`.
int EncodingSize(Encoding encoding);

/// Returns whether `id` is one of the protocol's control frames (manager, log, clock, debug,
/// maze, frame size: 7 to 15 and 127), which a frame table cannot take.
bool IsControlId(int id);

/// A data frame the decoder knows: its id and how its payload reads.
struct DataFrame {
  uint8_t id = 0;
  Encoding encoding = Encoding::kI16;
};

/// The original's incoming data frames: motor commands on ids 5 and 6.
std::vector<DataFrame> OriginalCommandFrames();

/// One complete frame from the firmware.
struct FirmwareFrame {
  uint8_t id = 0;
  int value = 0;              ///< motor or int16 data frame (clamped), manager code, or 0
  std::string text;           ///< log line, or a debug value's name
  float number = 0;           ///< float32 data frame, or debug value
  std::vector<uint8_t> data;  ///< debug walls (x, y, walls, known), visited (x, y), path (x, y...)
  bool is_data = false;       ///< a data frame of the table, read into `value` or `number`
  /// a log line (id UNIMOUSE_ID_LOG) the firmware wrote as plain text, not as a log frame:
  /// Serial.print on a board
  bool plain_text = false;
  Encoding encoding = Encoding::kI16;  ///< a data frame's encoding
  /// Returns a data frame's value as a signal.
  double Signal() const {
    return encoding == Encoding::kF32 ? static_cast<double>(number) : static_cast<double>(value);
  }
};

class FrameDecoder {
 public:
  /// Decodes the protocol's control frames and the data frames listed, whose ids must not be
  /// control ids.
  explicit FrameDecoder(std::vector<DataFrame> data_frames = OriginalCommandFrames());

  /// Consumes `bytes`, appending every frame they complete to `out`.
  void Feed(std::span<const uint8_t> bytes, std::vector<FirmwareFrame>& out);

  uint64_t frames() const { return frames_; }
  uint64_t unknown_bytes() const { return unknown_bytes_; }
  /// Lines of plain text read between frames (FirmwareFrame::plain_text).
  uint64_t text_lines() const { return text_lines_; }
  /// Ids seen that neither the protocol nor the data frames define for this direction, each
  /// once, in order.
  const std::vector<uint8_t>& unknown_ids() const { return unknown_ids_; }
  /// Throws away a partial frame, as after a reconnection; the counters stay.
  void Reset() {
    pending_.clear();
    skipping_log_ = false;
    text_.clear();
    in_text_ = false;
    after_cr_ = false;
  }

 private:
  // the data frame with this id, or null
  const DataFrame* Data(uint8_t id) const;
  // takes a byte of plain text; false when it ends the text and is a frame's first byte
  bool TakeText(uint8_t byte, std::vector<FirmwareFrame>& out);
  void EndText(std::vector<FirmwareFrame>& out);

  std::vector<DataFrame> data_frames_;
  // bytes of the frame being assembled, its id first
  std::vector<uint8_t> pending_;
  bool skipping_log_ = false;  // inside an overlong log line, until its 0x00
  // plain text between frames: printable bytes where a frame's id would be (no id the
  // firmware sends is printable), to the end of the line
  std::string text_;
  bool in_text_ = false;
  bool after_cr_ = false;  // a line just ended at '\r': a '\n' next belongs to it
  uint64_t text_lines_ = 0;
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
/// Appends a data frame carrying `value` in `encoding`; `tof_full_scale_m` serves kTof.
void PutDataFrame(uint8_t id, Encoding encoding, double value, double tof_full_scale_m,
                  std::string& out);
/// Appends a clock frame: sim time in microseconds, modulo 2^32.
void PutClockFrame(uint64_t time_us, std::string& out);
/// Appends a maze info frame: width and height in cells, the cell's side in whole millimetres,
/// the goal rectangle (a world has at most 128 cells a side, so each fits a byte).
void PutMazeInfoFrame(const BindContext::MazeInfo& maze, std::string& out);
/// Appends a frame size frame: a data frame's id and its payload bytes in `encoding`.
void PutFrameSizeFrame(uint8_t id, Encoding encoding, std::string& out);

}  // namespace unimouse::link

#endif  // UNIMOUSE_PLUGINS_LINK_FRAME_CODEC_H_
