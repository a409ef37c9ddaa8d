// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as a recording for `unimouse replay` (someone else's run.mcap): a recording or an
// InputError, nothing else; a recording read has a pose for each of its robots, in time order
// where the file had them so.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "recording.h"
#include "unimouse/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const unimouse::Recording recording = unimouse::ParseRecording(bytes, "fuzz.mcap");
    for (const unimouse::RecordedRobot& robot : recording.robots) {
      if (robot.poses.empty()) std::abort();
      // a time between the first and last pose gives a pose, whatever the file held
      (void)unimouse::PoseAt(robot, (robot.poses.front().t_s + robot.poses.back().t_s) / 2);
    }
  } catch (const unimouse::InputError&) {
  }
  return 0;
}
