// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_codec.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace unimouse::link {
namespace {

constexpr size_t kNameMax = 32;

// the control frames a firmware may send; data frames come from the table
bool ControlFromFirmware(uint8_t id) {
  return id == UNIMOUSE_ID_MANAGER || id == UNIMOUSE_ID_LOG || id == UNIMOUSE_ID_DEBUG_WALLS ||
         id == UNIMOUSE_ID_DEBUG_VISITED || id == UNIMOUSE_ID_DEBUG_PATH ||
         id == UNIMOUSE_ID_DEBUG_VALUE || id == UNIMOUSE_ID_MAZE_SIZE;
}

uint16_t ToWord(long v) { return static_cast<uint16_t>(static_cast<int16_t>(v)); }

// round half away from zero, then clamp; NaN reads as 0
long RoundClamped(double value, long min, long max) {
  if (std::isnan(value)) return 0;
  return static_cast<long>(
      std::round(std::clamp(value, static_cast<double>(min), static_cast<double>(max))));
}

}  // namespace

int EncodingSize(Encoding encoding) { return encoding == Encoding::kF32 ? 4 : 2; }

bool IsControlId(int id) {
  return (id >= UNIMOUSE_ID_MANAGER && id <= UNIMOUSE_ID_MAZE_SIZE) || id == UNIMOUSE_ID_FRAME_SIZE;
}

std::vector<DataFrame> OriginalCommandFrames() {
  return {{UNIMOUSE_ID_MOTOR_LEFT, Encoding::kMotor}, {UNIMOUSE_ID_MOTOR_RIGHT, Encoding::kMotor}};
}

FrameDecoder::FrameDecoder(std::vector<DataFrame> data_frames)
    : data_frames_(std::move(data_frames)) {}

const DataFrame* FrameDecoder::Data(uint8_t id) const {
  for (const DataFrame& d : data_frames_) {
    if (d.id == id) return &d;
  }
  return nullptr;
}

void FrameDecoder::EndText(std::vector<FirmwareFrame>& out) {
  FirmwareFrame line;
  line.id = UNIMOUSE_ID_LOG;
  line.plain_text = true;
  line.text = std::move(text_);
  out.push_back(std::move(line));
  ++text_lines_;
  text_.clear();
  in_text_ = false;
}

bool FrameDecoder::TakeText(uint8_t byte, std::vector<FirmwareFrame>& out) {
  if (byte == '\r' || byte == '\n') {
    EndText(out);
    after_cr_ = byte == '\r';
    return true;
  }
  if ((byte >= 0x20 && byte < 0x7f) || byte == '\t') {
    text_.push_back(static_cast<char>(byte));
    // as an overlong log frame: cut, the rest on a line of its own
    if (text_.size() == UNIMOUSE_LOG_MAX) EndText(out);
    return true;
  }
  // a print without its newline, then a frame
  EndText(out);
  return false;
}

void FrameDecoder::Feed(std::span<const uint8_t> bytes, std::vector<FirmwareFrame>& out) {
  for (const uint8_t byte : bytes) {
    if (skipping_log_) {
      skipping_log_ = byte != 0;
      continue;
    }
    if (in_text_ && TakeText(byte, out)) continue;
    if (pending_.empty()) {
      // println ends its line with "\r\n"
      const bool line_end = after_cr_ && byte == '\n';
      after_cr_ = false;
      if (line_end) continue;
      const bool known = ControlFromFirmware(byte) || Data(byte) != nullptr;
      if (!known && byte >= 0x20 && byte < 0x7f) {
        in_text_ = true;
        text_.push_back(static_cast<char>(byte));
        continue;
      }
      if (!known) {
        ++unknown_bytes_;
        if (std::find(unknown_ids_.begin(), unknown_ids_.end(), byte) == unknown_ids_.end()) {
          unknown_ids_.push_back(byte);
        }
        continue;
      }
      pending_.push_back(byte);
      continue;
    }
    pending_.push_back(byte);
    const uint8_t id = pending_[0];
    const uint8_t* payload = pending_.data() + 1;
    const size_t size = pending_.size() - 1;
    FirmwareFrame frame;
    frame.id = id;
    bool complete = false;
    if (const DataFrame* d = Data(id)) {
      if (size == static_cast<size_t>(EncodingSize(d->encoding))) {
        frame.is_data = true;
        frame.encoding = d->encoding;
        if (d->encoding == Encoding::kF32) {
          const uint32_t bits = unimouse_get_u32(payload);
          std::memcpy(&frame.number, &bits, 4);
        } else {
          const auto word = static_cast<int16_t>(unimouse_get_u16(payload));
          frame.value = d->encoding == Encoding::kMotor ? unimouse_clamp_motor(word) : word;
        }
        complete = true;
      }
    } else {
      switch (id) {
        case UNIMOUSE_ID_MANAGER:
          frame.value = payload[0];
          complete = true;
          break;
        case UNIMOUSE_ID_LOG:
          // a line ends at 0x00; an overlong one is cut there and the rest of it dropped
          if (byte == 0 || size > UNIMOUSE_LOG_MAX) {
            frame.text.assign(reinterpret_cast<const char*>(payload), size - 1);
            complete = true;
            skipping_log_ = byte != 0;
          }
          break;
        case UNIMOUSE_ID_DEBUG_WALLS:
        case UNIMOUSE_ID_DEBUG_VISITED:
        case UNIMOUSE_ID_MAZE_SIZE:
          if (size == static_cast<size_t>(unimouse_payload_size(id))) {
            frame.data.assign(payload, payload + size);
            complete = true;
          }
          break;
        case UNIMOUSE_ID_DEBUG_PATH:
          if (size == 1u + 2u * payload[0]) {
            frame.data.assign(payload + 1, payload + size);
            complete = true;
          }
          break;
        case UNIMOUSE_ID_DEBUG_VALUE:
          if (size > 4 && (byte == 0 || size > 4 + kNameMax)) {
            std::memcpy(&frame.number, payload, 4);
            frame.text.assign(reinterpret_cast<const char*>(payload + 4), size - 4 - (byte == 0));
            complete = true;
          }
          break;
      }
    }
    if (!complete) continue;
    out.push_back(std::move(frame));
    ++frames_;
    pending_.clear();
  }
}

void PutSensorFrame(uint8_t id, uint16_t value, std::string& out) {
  uint8_t frame[3] = {id, 0, 0};
  unimouse_put_u16(frame + 1, value);
  out.append(reinterpret_cast<const char*>(frame), 3);
}

void PutTofFrame(uint8_t id, double distance_m, double full_scale_m, std::string& out) {
  PutSensorFrame(id, unimouse_tof_to_counts(distance_m, full_scale_m), out);
}

void PutEncoderFrame(uint8_t id, long counts, std::string& out) {
  PutSensorFrame(id, ToWord(std::clamp<long>(counts, INT16_MIN, INT16_MAX)), out);
}

void PutDataFrame(uint8_t id, Encoding encoding, double value, double tof_full_scale_m,
                  std::string& out) {
  switch (encoding) {
    case Encoding::kTof:
      PutTofFrame(id, value, tof_full_scale_m, out);
      return;
    case Encoding::kI16:
      PutSensorFrame(id, ToWord(RoundClamped(value, INT16_MIN, INT16_MAX)), out);
      return;
    case Encoding::kMotor:
      PutSensorFrame(id, ToWord(RoundClamped(value, -UNIMOUSE_MOTOR_MAX, UNIMOUSE_MOTOR_MAX)), out);
      return;
    case Encoding::kF32: {
      const auto f = static_cast<float>(value);
      uint32_t bits = 0;
      std::memcpy(&bits, &f, 4);
      uint8_t frame[5] = {id};
      unimouse_put_u32(frame + 1, bits);
      out.append(reinterpret_cast<const char*>(frame), 5);
      return;
    }
  }
}

void PutClockFrame(uint64_t time_us, std::string& out) {
  uint8_t frame[5] = {UNIMOUSE_ID_CLOCK};
  unimouse_put_u32(frame + 1, static_cast<uint32_t>(time_us));
  out.append(reinterpret_cast<const char*>(frame), 5);
}

void PutMazeInfoFrame(const BindContext::MazeInfo& maze, std::string& out) {
  uint8_t frame[9] = {UNIMOUSE_ID_MAZE_INFO, static_cast<uint8_t>(maze.width_cells),
                      static_cast<uint8_t>(maze.height_cells)};
  unimouse_put_u16(frame + 3, static_cast<uint16_t>(std::lround(maze.cell_m * 1000)));
  frame[5] = static_cast<uint8_t>(maze.goal_x0);
  frame[6] = static_cast<uint8_t>(maze.goal_y0);
  frame[7] = static_cast<uint8_t>(maze.goal_x1);
  frame[8] = static_cast<uint8_t>(maze.goal_y1);
  out.append(reinterpret_cast<const char*>(frame), sizeof(frame));
}

void PutFrameSizeFrame(uint8_t id, Encoding encoding, std::string& out) {
  const uint8_t frame[3] = {UNIMOUSE_ID_FRAME_SIZE, id,
                            static_cast<uint8_t>(EncodingSize(encoding))};
  out.append(reinterpret_cast<const char*>(frame), sizeof(frame));
}

}  // namespace unimouse::link
