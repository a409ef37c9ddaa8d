// SPDX-License-Identifier: GPL-3.0-or-later
// The VL53L0X model of table 3.8 in a real maze corridor: unbiased readings whose standard
// deviation is c_v times the distance (the "model" column of table 3.7), the blind zone and the
// full-scale value, the 45-degree side sensors, and reproducible noise.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "inline_assets.h"
#include "plugin_rig.h"

namespace unimouse {
namespace {

using testing::BundledRobotWith;
using testing::MakeKernel;
using testing::SignalValue;

constexpr double kCv = 0.028084;          // table 3.8
constexpr double kNorthFace_m = 1.794;    // 10 cells of 0.18 m, minus half a wall
constexpr double kSensorAhead_m = 0.060;  // the front sensor sits on the plate's front edge

// a corridor one cell wide and ten long
Maze Corridor() {
  std::string text = "o---o\n";
  for (int i = 0; i < 10; ++i) text += i == 9 ? "| S |\no---o\n" : "|   |\no   o\n";
  return ParseMazeText(text, "corridor.txt");
}

std::string Sensor(const std::string& name, const std::string& site) {
  return "  - { type: unimouse.tof_sensor, name: " + name +
         ", period_s: 0.001, params: { site: " + site + ", range_out: " + name +
         ".m, true_range_out: " + name + ".true_m } }\n";
}

class TofSensorTest : public ::testing::Test {
 protected:
  // readings of `sensor` with the robot facing north, its front sensor `gap_m` from the wall
  std::vector<double> Readings(double gap_m, int samples, uint64_t seed = 1,
                               const std::string& sensor = "front") {
    KernelOptions options;
    options.seed = seed;
    options.spawn = Pose2D{0.09, kNorthFace_m - kSensorAhead_m - gap_m, std::numbers::pi / 2};
    auto kernel =
        MakeKernel(BundledRobotWith(Sensor("front", "tof_front") + Sensor("left", "tof_left") +
                                    Sensor("right", "tof_right"))
                       .text,
                   &maze_, options);
    for (int i = 0; i < 100; ++i) kernel->Step();  // let the robot settle on its wheels
    std::vector<double> out;
    true_m_ = SignalValue(*kernel, sensor + ".true_m");
    for (int i = 0; i < samples; ++i) {
      kernel->Step();
      out.push_back(SignalValue(*kernel, sensor + ".m"));
    }
    return out;
  }

  const Maze maze_ = Corridor();
  double true_m_ = 0;
};

TEST_F(TofSensorTest, ReadingsAreUnbiasedWithSpreadProportionalToDistance) {
  for (double d : {0.05, 0.10, 0.20, 0.30, 0.40}) {
    const std::vector<double> r = Readings(d, 2000);
    ASSERT_NEAR(true_m_, d, 1e-3) << "the robot is not where the test put it";
    double sum = 0, squares = 0;
    for (double x : r) sum += x;
    const double n = static_cast<double>(r.size());
    const double mean = sum / n;
    for (double x : r) squares += (x - mean) * (x - mean);
    const double sd = std::sqrt(squares / (n - 1));
    EXPECT_NEAR(mean, true_m_, 0.005 * true_m_) << d;
    EXPECT_NEAR(sd, kCv * true_m_, 0.10 * kCv * true_m_) << d;
  }
}

TEST_F(TofSensorTest, InsideTheBlindZoneItReportsNoTarget) {
  for (double x : Readings(0.02, 100)) EXPECT_EQ(x, 1.2);
}

TEST_F(TofSensorTest, BeyondMaximumRangeItReportsNoTarget) {
  for (double x : Readings(1.5, 100)) EXPECT_EQ(x, 1.2);
  EXPECT_EQ(true_m_, -1);
}

TEST_F(TofSensorTest, SideSensorsSeeTheSideWallsAlongTheirDiagonal) {
  // centred in a cell: each side sensor is 0.09 - 0.048 - 0.006 = 0.036 m from its wall face,
  // and its beam, yawed 45 degrees, meets the face after 0.036 / cos(45 deg)
  const double expected = 0.036 / std::cos(std::numbers::pi / 4);
  for (const char* side : {"left", "right"}) {
    const std::vector<double> r = Readings(0.5, 2000, 1, side);
    EXPECT_NEAR(true_m_, expected, 5e-4) << side;
    double sum = 0;
    for (double x : r) sum += x;
    EXPECT_NEAR(sum / static_cast<double>(r.size()), expected, 0.005 * expected) << side;
  }
}

TEST_F(TofSensorTest, SameSeedGivesTheSameSamples) {
  EXPECT_EQ(Readings(0.2, 300, 9), Readings(0.2, 300, 9));
  EXPECT_NE(Readings(0.2, 300, 9), Readings(0.2, 300, 10));
}

TEST_F(TofSensorTest, SamplesEvery30MillisecondsByDefault) {
  KernelOptions options;
  options.spawn = Pose2D{0.09, 1.2, std::numbers::pi / 2};  // 0.53 m from the north wall
  auto kernel = MakeKernel(BundledRobotWith("  - { type: unimouse.tof_sensor, name: f, params: { "
                                            "site: tof_front, range_out: f.m } }\n")
                               .text,
                           &maze_, options);
  std::vector<double> changes;
  double last = SignalValue(*kernel, "f.m");
  for (int i = 0; i < 300; ++i) {
    kernel->Step();
    const double now = SignalValue(*kernel, "f.m");
    if (now != last) changes.push_back(i);
    last = now;
  }
  // steps 0, 30, 60, ... : 10 fresh noisy samples in 300 steps
  ASSERT_EQ(changes.size(), 10u);
  EXPECT_EQ(changes[1] - changes[0], 30);
}

}  // namespace
}  // namespace unimouse
