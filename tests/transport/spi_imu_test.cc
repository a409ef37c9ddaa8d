// SPDX-License-Identifier: GPL-3.0-or-later
// The MPU-6500 on the emulated Mega 2560's SPI bus, driven by an ordinary driver on Arduino's
// SPI library (tests/avr/imu_spi.ino) on the gyro robot: WHO_AM_I, what the chip answers
// before its start-up time, the full-scale range the firmware selects, and a 90-degree turn
// integrated from gyro z within 2 degrees of the turn the simulator saw; and the link's bad
// input for the bus.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "inline_assets.h"
#include "run_program.h"
#include "text_file.h"
#include "transport.h"

namespace unimouse {
namespace {

using testing::Outcome;
using testing::RunResult;

class SpiImuTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string image = UNIMOUSE_AVR_TEST_FIRMWARE_DIR "/imu_spi.elf";
    if (!std::filesystem::exists(image)) return;
    run_ = new RunResult(
        testing::UnimouseRun("--robot unimouse-gyro --duration 2.5 --link avr:" + image +
                                 " --link-set spi_imu=mpu6500 --link-set spi_imu_cs_pin=PB0",
                             "unimouse_spi_imu"));
    log_ = new std::string(ReadTextFile(
        (std::filesystem::temp_directory_path() / "unimouse_spi_imu" / "log.txt").string()));
  }
  static void TearDownTestSuite() {
    delete run_;
    delete log_;
  }
  void SetUp() override {
    if (run_ == nullptr) GTEST_SKIP() << "no AVR test firmware (gcc-avr, arduino-core-avr)";
    ASSERT_EQ(run_->outcome.exit_code, 0) << run_->outcome.output;
  }
  static RunResult* run_;
  static std::string* log_;
};
RunResult* SpiImuTest::run_ = nullptr;
std::string* SpiImuTest::log_ = nullptr;

TEST_F(SpiImuTest, WhoAmIReadsTheMpu6500sIdOnceTheChipIsUp) {
  EXPECT_NE(log_->find("who_am_i at 150 ms: 0x70"), std::string::npos) << *log_;
}

TEST_F(SpiImuTest, BeforeItsStartUpTimeTheChipDoesNotAnswerAndTheMcuReadsZero) {
  EXPECT_NE(log_->find("who_am_i at 0 ms: 0x00"), std::string::npos) << *log_;
}

TEST_F(SpiImuTest, RegistersKeepWhatTheDriverWrote) {
  EXPECT_NE(log_->find("gyro_config: 0x18, pwr_mgmt_1: 0x01"), std::string::npos) << *log_;
}

TEST_F(SpiImuTest, GyroZIntegratedByTheDriverGivesTheTrueTurnWithinTwoDegrees) {
  const size_t at = log_->find("spi gyro turn: ");
  ASSERT_NE(at, std::string::npos) << *log_;
  const double gyro_deg = std::stod(log_->substr(at + 15));
  // the robot starts facing north on an open floor
  const double true_deg =
      std::remainder(run_->result["robot_pose"]["yaw_rad"].get<double>() - std::numbers::pi / 2,
                     2 * std::numbers::pi) *
      180 / std::numbers::pi;
  EXPECT_NEAR(true_deg, 90, 5) << "the driver did not turn about 90 degrees";
  EXPECT_NEAR(gyro_deg, true_deg, 2.0);
}

// the ICM-20602 powers up asleep: a driver that never clears SLEEP reads its ID and its
// configuration back, and zeros from the data registers, as from the real chip
TEST(SpiImuIcm20602Test, ADriverThatNeverWakesTheChipReadsZerosFromItsDataRegisters) {
  const std::string image = UNIMOUSE_AVR_TEST_FIRMWARE_DIR "/imu_spi_no_wake.elf";
  if (!std::filesystem::exists(image)) GTEST_SKIP() << "no AVR test firmware";
  const RunResult r = testing::UnimouseRun(
      "--robot unimouse-gyro --duration 2.5 --link avr:" + image + " --link-set spi_imu=icm20602",
      "unimouse_spi_imu_asleep");
  ASSERT_EQ(r.outcome.exit_code, 0) << r.outcome.output;
  const std::string log = ReadTextFile(
      (std::filesystem::temp_directory_path() / "unimouse_spi_imu_asleep" / "log.txt").string());
  EXPECT_NE(log.find("who_am_i at 150 ms: 0x12"), std::string::npos) << log;
  EXPECT_NE(log.find("gyro_config: 0x18, pwr_mgmt_1: 0x41"), std::string::npos) << log;
  EXPECT_NE(log.find("spi gyro turn: 0.0 deg"), std::string::npos) << log;
}

TEST(SpiImuInputTest, PartsAndPinsAreCheckedAgainstTheMcu) {
  EXPECT_EQ(link::SpiImuPartProblem("mpu6500"), "");
  EXPECT_EQ(link::SpiImuPartProblem("icm20602"), "");
  EXPECT_NE(link::SpiImuPartProblem("bmi088"), "");
  EXPECT_EQ(link::PinProblem("atmega2560", "PB0"), "");
  EXPECT_EQ(link::PinProblem("atmega2560", "PL7"), "");
  EXPECT_EQ(link::PinProblem("atmega2560", "PI0"), "atmega2560 has no pin PI0");
  EXPECT_EQ(link::PinProblem("atmega2560", "PG6"), "atmega2560 has no pin PG6");
  EXPECT_EQ(link::PinProblem("atmega328p", "PA0"), "atmega328p has no pin PA0");
  EXPECT_EQ(link::PinProblem("atmega328p", "PC7"), "atmega328p has no pin PC7");
  EXPECT_NE(link::PinProblem("atmega2560", "53"), "");
}

TEST(SpiImuInputTest, AChipSelectPinTheMcuDoesNotHaveIsBadInputAtItsLineFromCheck) {
  // a robot file may name a board on a serial port, which check never opens
  const std::string text = testing::GyroRobotWith(
      "  - { type: unimouse.imu, name: imu, params: { site: imu } }\n"
      "  - { type: unimouse.link, name: link, params: { transport: 'serial:/dev/ttyUSB9@1000000', "
      "mcu: atmega328p, spi_imu: mpu6500, spi_imu_cs_pin: PA2 } }\n");
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  const std::string path = testing::FreshDirectory("spi_imu_pin") + "/robot.yaml";
  std::ofstream(path) << text;
  const Outcome o = testing::Unimouse("check " + path);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(path + ":" + std::to_string(line) + ":"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("atmega328p has no pin PA2"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace unimouse
