// SPDX-License-Identifier: GPL-3.0-or-later
#include "frame_codec.h"

#include <algorithm>
#include <cstring>

namespace unimouse::link {
namespace {

constexpr size_t kNameMax = 32;

bool FromFirmware(uint8_t id) {
  return id == UNIMOUSE_ID_MOTOR_LEFT || id == UNIMOUSE_ID_MOTOR_RIGHT ||
         id == UNIMOUSE_ID_MANAGER || id == UNIMOUSE_ID_LOG || id == UNIMOUSE_ID_DEBUG_WALLS ||
         id == UNIMOUSE_ID_DEBUG_VISITED || id == UNIMOUSE_ID_DEBUG_PATH ||
         id == UNIMOUSE_ID_DEBUG_VALUE;
}

}  // namespace

void FrameDecoder::Feed(std::span<const uint8_t> bytes, std::vector<FirmwareFrame>& out) {
  for (const uint8_t byte : bytes) {
    if (skipping_log_) {
      skipping_log_ = byte != 0;
      continue;
    }
    if (pending_.empty()) {
      if (!FromFirmware(byte)) {
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
    switch (id) {
      case UNIMOUSE_ID_MOTOR_LEFT:
      case UNIMOUSE_ID_MOTOR_RIGHT:
        if (size == 2) {
          frame.value = unimouse_clamp_motor(static_cast<int16_t>(unimouse_get_u16(payload)));
          complete = true;
        }
        break;
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
  const long clamped = std::clamp<long>(counts, INT16_MIN, INT16_MAX);
  PutSensorFrame(id, static_cast<uint16_t>(static_cast<int16_t>(clamped)), out);
}

void PutClockFrame(uint64_t time_us, std::string& out) {
  uint8_t frame[5] = {UNIMOUSE_ID_CLOCK};
  unimouse_put_u32(frame + 1, static_cast<uint32_t>(time_us));
  out.append(reinterpret_cast<const char*>(frame), 5);
}

}  // namespace unimouse::link
