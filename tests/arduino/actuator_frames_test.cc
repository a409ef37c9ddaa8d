// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's frames to the simulator, on the PC, against golden bytes: motor
// commands clamped to 10 bits, sent on change and again every 50 ms (so the simulator's 100 ms
// failsafe never trips on a steady command); log lines ended by 0x00 and cut at 255 bytes.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "SimulationActuators.h"
#include "byte_stream.h"

namespace unimouse {
namespace {

TEST(FirmwareActuatorFramesTest, MotorCommandsAreClampedAndSentOnChange) {
  ByteStream stream;
  StreamActuatorManager manager(stream);
  MotorActuator left(manager, UNIMOUSE_ID_MOTOR_LEFT);
  left.setCommand(-300, 0);
  left.setCommand(-300, 1);  // unchanged: nothing
  left.setCommand(5000, 2);  // clamped to 1023
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{5, 0xD4, 0xFE, 5, 0xFF, 0x03}));
  EXPECT_EQ(left.getCommand(), 1023);
}

TEST(FirmwareActuatorFramesTest, ASteadyCommandIsResentEvery50Ms) {
  ByteStream stream;
  StreamActuatorManager manager(stream);
  MotorActuator right(manager, UNIMOUSE_ID_MOTOR_RIGHT);
  right.refresh(0);  // nothing set yet: nothing to resend
  EXPECT_TRUE(stream.out.empty());
  right.setCommand(0, 10);  // the first command goes out even if it is 0
  int frames = 1;
  for (uint32_t ms = 11; ms <= 210; ++ms) right.refresh(ms);
  frames += 4;  // at 60, 110, 160 and 210 ms
  EXPECT_EQ(stream.out.size(), static_cast<size_t>(3 * frames));
  // across the 32-bit millis wrap-around too
  right.setCommand(7, 0xFFFFFFF0u);
  const size_t before = stream.out.size();
  right.refresh(0x00000022u);  // 50 ms later
  EXPECT_EQ(stream.out.size(), before + 3);
}

TEST(FirmwareActuatorFramesTest, LogLinesEndAtTheirFirstZeroAndAreCutAt255Bytes) {
  ByteStream stream;
  StreamActuatorManager manager(stream);
  SimulationLogger logger(manager);
  logger.log("hi");
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{8, 'h', 'i', 0}));
  stream.out.clear();
  const std::string longer(300, 'x');
  logger.log(longer.c_str());
  ASSERT_EQ(stream.out.size(), 1u + 255u + 1u);
  EXPECT_EQ(stream.out.front(), 8);
  EXPECT_EQ(stream.out.back(), 0);
  EXPECT_EQ(stream.out[255], 'x');
}

}  // namespace
}  // namespace unimouse
