// SPDX-License-Identifier: GPL-3.0-or-later
// The firmware library's frame reading, on the PC: frames split across reads anywhere are put
// back together without waiting, frames of unregistered ids are skipped whole, bytes that start
// no frame are stepped over, and after garbage the reader is back in step at the next frames.
// Encoder totals are 32-bit.
#include <gtest/gtest.h>

#include <vector>

#include "SimulationSensors.h"
#include "byte_stream.h"

namespace unimouse {
namespace {

std::vector<uint8_t> Tof(uint8_t id, uint16_t counts) {
  return {id, static_cast<uint8_t>(counts & 0xFF), static_cast<uint8_t>(counts >> 8)};
}

std::vector<uint8_t> Encoder(uint8_t id, int16_t delta) {
  return Tof(id, static_cast<uint16_t>(delta));
}

struct Rig {
  ByteStream stream;
  StreamSimulationSensorManager<4> manager{stream};
  DistanceSensor left{UNIMOUSE_ID_TOF_LEFT}, front{UNIMOUSE_ID_TOF_FRONT};
  EncoderSensor encoder{UNIMOUSE_ID_ENCODER_LEFT};
  Rig() {
    manager.addSensor(left);
    manager.addSensor(front);
    manager.addSensor(encoder);
  }
};

TEST(FirmwareSensorFramesTest, AFrameSplitAtEveryByteIsAssembledWithoutWaiting) {
  Rig rig;
  const std::vector<uint8_t> bytes = Tof(UNIMOUSE_ID_TOF_FRONT, 32768);  // 0.6 m of 1.2 m
  for (uint8_t b : bytes) {
    EXPECT_FALSE(rig.front.hasNewData());
    rig.stream.Arrive({b});
    rig.manager.updateSensors();  // returns with what there is
  }
  EXPECT_TRUE(rig.front.hasNewData());
  EXPECT_NEAR(rig.front.distance(), 32768 * 1.2 / 65535, 1e-6);
  EXPECT_FALSE(rig.left.hasNewData());
}

// a robot with a fourth ToF sensor sends it as frame 17; its payload bytes 0x09 0x02 would read
// as the start of a clock frame and of a front ToF frame, had the reader not learnt its size
TEST(FirmwareSensorFramesTest, AFrameTheSimulatorDeclaredIsSteppedOverByItsDeclaredSize) {
  Rig rig;
  const std::vector<uint8_t> extra = Tof(17, 0x0209);
  std::vector<uint8_t> bytes = {UNIMOUSE_ID_FRAME_SIZE, 17, 2};
  for (int i = 0; i < 3; ++i) {
    bytes.insert(bytes.end(), extra.begin(), extra.end());
    const std::vector<uint8_t> front = Tof(UNIMOUSE_ID_TOF_FRONT, static_cast<uint16_t>(1000 + i));
    bytes.insert(bytes.end(), front.begin(), front.end());
  }
  rig.stream.Arrive(bytes);
  rig.manager.updateSensors();
  EXPECT_EQ(rig.manager.payloadSize(17), 2);
  EXPECT_EQ(rig.manager.unclaimedFrames(), 3u);
  EXPECT_EQ(rig.manager.skippedBytes(), 0u);
  EXPECT_NEAR(rig.front.distance(), 1002 * 1.2 / 65535, 1e-6);

  // and a sketch that reads it registers a sensor of that id
  DistanceSensor rear{17};
  rig.manager.addSensor(rear);
  rig.stream.Arrive(Tof(17, 32768));
  rig.manager.updateSensors();
  EXPECT_TRUE(rear.hasNewData());
  EXPECT_NEAR(rear.distance(), 32768 * 1.2 / 65535, 1e-6);
}

TEST(FirmwareSensorFramesTest, UnregisteredIdsAreSkippedWholeAndNonIdsSteppedOver) {
  Rig rig;
  std::vector<uint8_t> bytes = Tof(UNIMOUSE_ID_TOF_RIGHT, 0x0707);     // nobody listens to right
  bytes.push_back(0xEE);                                               // no id at all
  bytes.push_back(UNIMOUSE_ID_LOG);                                    // no sim -> MCU id
  const std::vector<uint8_t> clock = {UNIMOUSE_ID_CLOCK, 1, 2, 3, 4};  // unregistered, 4 bytes
  bytes.insert(bytes.end(), clock.begin(), clock.end());
  const std::vector<uint8_t> left = Tof(UNIMOUSE_ID_TOF_LEFT, 1000);
  bytes.insert(bytes.end(), left.begin(), left.end());
  rig.stream.Arrive(bytes);
  rig.manager.updateSensors();
  EXPECT_EQ(rig.manager.unclaimedFrames(), 2u);
  EXPECT_EQ(rig.manager.skippedBytes(), 2u);
  EXPECT_TRUE(rig.left.hasNewData());
  EXPECT_NEAR(rig.left.distance(), 1000 * 1.2 / 65535, 1e-6);
}

TEST(FirmwareSensorFramesTest, AfterGarbageTheReaderIsBackInStepAndNeverHangs) {
  Rig rig;
  // seeded garbage; then four bytes that are no id, which finish any frame the garbage left
  // open (4 payload bytes at most) and are otherwise stepped over; then frames that must arrive
  uint32_t state = 12345;
  std::vector<uint8_t> garbage;
  for (int i = 0; i < 500; ++i) {
    state = state * 1664525u + 1013904223u;
    garbage.push_back(static_cast<uint8_t>(state >> 24));
  }
  rig.stream.Arrive(garbage);
  rig.manager.updateSensors();
  EXPECT_EQ(rig.stream.available(), 0);  // all read, nothing waited for
  rig.stream.Arrive({0xEE, 0xEE, 0xEE, 0xEE});
  rig.manager.updateSensors();
  rig.front.hasNewData();  // forget what the garbage delivered
  const int32_t before = rig.encoder.count();
  std::vector<uint8_t> frames = Tof(UNIMOUSE_ID_TOF_FRONT, 2000);
  const std::vector<uint8_t> enc = Encoder(UNIMOUSE_ID_ENCODER_LEFT, -300);
  frames.insert(frames.end(), enc.begin(), enc.end());
  rig.stream.Arrive(frames);
  rig.manager.updateSensors();
  EXPECT_TRUE(rig.front.hasNewData());
  EXPECT_NEAR(rig.front.distance(), 2000 * 1.2 / 65535, 1e-6);
  EXPECT_EQ(rig.encoder.count() - before, -300);
}

TEST(FirmwareSensorFramesTest, EncoderTotalsPassSixteenBitsAndReadResetGivesTheCountsSince) {
  Rig rig;
  for (int i = 0; i < 100; ++i) rig.stream.Arrive(Encoder(UNIMOUSE_ID_ENCODER_LEFT, 1000));
  rig.manager.updateSensors();
  EXPECT_EQ(rig.encoder.count(), 100000);  // an int16 accumulator would have wrapped
  EXPECT_EQ(rig.encoder.readReset(), 100000);
  rig.stream.Arrive(Encoder(UNIMOUSE_ID_ENCODER_LEFT, -5));
  rig.manager.updateSensors();
  EXPECT_EQ(rig.encoder.readReset(), -5);
  EXPECT_EQ(rig.encoder.count(), 99995);
}

TEST(FirmwareSensorFramesTest, NoTargetReadsAsTheFullScale) {
  Rig rig;
  rig.stream.Arrive(Tof(UNIMOUSE_ID_TOF_FRONT, UNIMOUSE_TOF_NO_TARGET));
  rig.manager.updateSensors();
  EXPECT_FLOAT_EQ(rig.front.distance(), 1.2f);
}

TEST(FirmwareSensorFramesTest, ImuFramesCarrySignedCountsReadInSiAtTheChipsSensitivity) {
  // an ICM-20602 at +-2000 dps and +-4 g: 16.4 LSB/dps, 8192 LSB/g
  ByteStream stream;
  StreamSimulationSensorManager<6> manager{stream};
  ImuSensor imu;
  for (uint8_t i = 0; i < 6; ++i) manager.addSensor(imu.axis(i));
  stream.Arrive(Encoder(UNIMOUSE_ID_GYRO_Z, -1640));    // -100 dps
  stream.Arrive(Encoder(UNIMOUSE_ID_ACCEL_Z, 8192));    // 1 g
  stream.Arrive(Encoder(UNIMOUSE_ID_ACCEL_X, -32768));  // the register's end
  manager.updateSensors();
  EXPECT_EQ(imu.counts(2), -1640);
  EXPECT_NEAR(imu.gyroRadPerS(2), -100 * 3.14159265 / 180, 1e-5);
  EXPECT_NEAR(imu.accelMPerS2(2), 9.80665, 1e-5);
  EXPECT_NEAR(imu.accelMPerS2(0), -4 * 9.80665, 1e-4);
  EXPECT_EQ(imu.counts(1), 0);
  EXPECT_TRUE(imu.axis(2).hasNewData());
  EXPECT_FALSE(imu.axis(1).hasNewData());
}

}  // namespace
}  // namespace unimouse
