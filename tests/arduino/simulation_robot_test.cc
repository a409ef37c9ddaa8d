// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's facade on the PC, byte for byte: begin() asks for sensors (and
// lock-step) without waiting; update() delivers readings; in lock-step the commands loop() sends
// after a clock frame go out before that step's done byte, which the next update() sends.
#include <gtest/gtest.h>

#include <vector>

#include "UnimouseSim.h"
#include "byte_stream.h"

namespace {
unsigned long now_ms = 0;
}  // namespace

unsigned long millis() { return now_ms; }
unsigned long micros() { return now_ms * 1000; }
unsigned long unimousePcLibraryMillis() { return now_ms; }
void unimousePcClock(uint32_t) {}
void unimousePcAwaitInput() {}
void unimousePcSetIdle(void (*)(void*), void*) {}

namespace unimouse {
namespace {

TEST(FirmwareSimulationRobotTest, BeginAsksForSensorsAnnouncesItselfAndAsksForLockStep) {
  ByteStream stream;
  SimulationRobot robot(stream);
  robot.begin(true);
  // the sizes of the data frames, sensors on, "I resend my commands" (so silence may stop the
  // motors), lock-step on
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{7, 0x14, 7, 0x02, 7, 0x12, 7, 0x10}));
  EXPECT_FLOAT_EQ(robot.frontDistance(), 1.2f);  // nothing yet: the full scale
}

TEST(FirmwareSimulationRobotTest, InLockStepTheCommandsOfAStepComeBeforeItsDoneByte) {
  ByteStream stream;
  SimulationRobot robot(stream);
  robot.begin(true);
  stream.out.clear();
  // step 1: sensor frames, then the clock at 1 ms
  stream.Arrive({2, 0x00, 0x80, 3, 10, 0, 4, 12, 0, 9, 0xE8, 0x03, 0, 0});
  robot.update();
  EXPECT_TRUE(stream.out.empty());  // nothing is done before loop() had its say
  EXPECT_NEAR(robot.frontDistance(), 0x8000 * 1.2 / 65535, 1e-6);
  EXPECT_EQ(robot.leftEncoder(), 10);
  EXPECT_EQ(robot.rightEncoder(), 12);
  EXPECT_EQ(robot.simMicros(), 1000u);
  robot.motorLeft(300);
  robot.motorRight(-300);
  // step 2: its frames, then its clock
  stream.Arrive({3, 5, 0, 4, 5, 0});
  stream.Arrive({9, 0xD0, 0x07, 0, 0});
  robot.update();  // the next loop(): step 1 is done, and step 2 read
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{5, 0x2C, 0x01, 6, 0xD4, 0xFE, 7, 0x11}));
  EXPECT_EQ(robot.simMicros(), 2000u);
  EXPECT_EQ(robot.leftEncoder(), 5);
}

TEST(FirmwareSimulationRobotTest, WithoutLockStepSteadyCommandsAreResent) {
  ByteStream stream;
  SimulationRobot robot(stream);
  robot.begin(false);
  now_ms = 1000;
  robot.motorLeft(100);
  stream.out.clear();
  now_ms = 1049;
  robot.update();
  EXPECT_TRUE(stream.out.empty());
  now_ms = 1050;
  robot.update();
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{5, 100, 0}));
}

// firmware code written against the device interfaces (figures 3.17/3.18)
int32_t WallFollowTurn(const IDistanceSensor& left, float goal_m) {
  return static_cast<int32_t>(900 * (left.distance() - goal_m));
}

// what a real robot's adapter looks like: a driver's reading behind the same interface
class BoardToF : public IDistanceSensor {
 public:
  explicit BoardToF(uint16_t millimetres) : mm_(millimetres) {}
  float distance() const override { return mm_ / 1000.0f; }

 private:
  uint16_t mm_;
};

class RecordedMotor : public IMotor {
 public:
  void setCommand(int32_t command) override { last = command; }
  int32_t last = 0;
};

void Drive(IMotor& left, IMotor& right, int32_t turn) {
  left.setCommand(500 - turn);
  right.setCommand(500 + turn);
}

TEST(FirmwareDevicesTest, TheSameFirmwareCodeRunsOnSimulatedAndRealDevices) {
  ByteStream stream;
  SimulationRobot robot(stream);
  robot.begin(false);
  stream.Arrive({0, 0x00, 0x40});  // left: 0x4000 counts of 1.2 m = 0.300 m
  robot.update();
  EXPECT_EQ(WallFollowTurn(robot.leftSensor(), 0.2f), WallFollowTurn(BoardToF(300), 0.2f));
  stream.out.clear();
  Drive(robot.leftMotorActuator(), robot.rightMotorActuator(), 90);
  EXPECT_EQ(stream.out, (std::vector<uint8_t>{5, 0x9A, 0x01, 6, 0x4E, 0x02}));  // 410, 590
  RecordedMotor left, right;
  Drive(left, right, 90);
  EXPECT_EQ(left.last, 410);
  EXPECT_EQ(right.last, 590);
}

}  // namespace
}  // namespace unimouse
