// SPDX-License-Identifier: GPL-3.0-or-later
// The encoder of table 4.5 (12 CPR on a 29.86:1 motor shaft): 358.32 counts per wheel turn,
// signed, with algorithm 1's remainder carried so that counts never drift from the wheel angle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "plugin_rig.h"

namespace unimouse {
namespace {

using testing::JointAngle;
using testing::MakeKernel;
using testing::RigYaml;
using testing::SetSignal;
using testing::SignalValue;

constexpr double kCountsPerWheelTurn = 12 * 29.86;

std::string Drive(const std::string& encoder_extra = "") {
  return "  - { type: unimouse.dc_motor, name: m, params: { actuator: rotor_motor, voltage_in: "
         "volts } }\n"
         "  - { type: unimouse.encoder, name: e, params: { joint: rotor, counts_out: counts" +
         encoder_extra + " } }\n";
}

// what the encoder reported over a run, and the wheel turns it saw meanwhile
struct Tally {
  long counts = 0;
  double turns = 0;
};

// steps the rig, summing the deltas of an encoder that runs every `every` steps; the encoder
// senses before a step integrates, so it has seen the angle from before its last step
Tally Spin(Kernel& kernel, int steps, int every = 1) {
  const double start = JointAngle(kernel, "rotor");
  Tally t;
  for (int i = 0; i < steps; ++i) {
    const double seen = JointAngle(kernel, "rotor");
    const bool due = kernel.state().step() % every == 0;
    kernel.Step();
    if (due) {
      t.counts += std::lround(SignalValue(kernel, "counts"));
      t.turns = (seen - start) / (2 * std::numbers::pi);
    }
  }
  return t;
}

TEST(EncoderTest, CountsFollowWheelRevolutionsWithoutDriftOver1e5Steps) {
  auto kernel = MakeKernel(RigYaml(0, Drive()));
  SetSignal(*kernel, "volts", 6);
  const double start = JointAngle(*kernel, "rotor");
  long total = 0;
  for (int i = 1; i <= 100000; ++i) {
    const double seen = JointAngle(*kernel, "rotor");
    kernel->Step();
    total += std::lround(SignalValue(*kernel, "counts"));
    // within one count of the angle it has seen, at every checkpoint
    if (i % 10000 == 0) {
      const double turns = (seen - start) / (2 * std::numbers::pi);
      EXPECT_NEAR(static_cast<double>(total), std::round(kCountsPerWheelTurn * turns), 1.0) << i;
    }
  }
  // about 1200 wheel turns in 100 s at 75.9 rad/s
  EXPECT_GT(total, 400000);
}

TEST(EncoderTest, BackwardsRotationCountsNegative) {
  auto kernel = MakeKernel(RigYaml(0, Drive()));
  SetSignal(*kernel, "volts", -6);
  const Tally t = Spin(*kernel, 5000);
  EXPECT_LT(t.counts, 0);
  EXPECT_NEAR(static_cast<double>(t.counts), std::round(kCountsPerWheelTurn * t.turns), 1.0);
}

TEST(EncoderTest, FullSpeedGivesAboutFourCountsPerMillisecond) {
  auto kernel = MakeKernel(RigYaml(0, Drive()));
  SetSignal(*kernel, "volts", 6);
  Spin(*kernel, 1000);
  // 75.9 rad/s x 29.86 x 12 / 2 pi = 4.33 counts per 1 ms step
  const long counts = Spin(*kernel, 1000).counts;
  const double counts_per_s = 6 / 0.079025 * kCountsPerWheelTurn / (2 * std::numbers::pi);
  EXPECT_NEAR(static_cast<double>(counts) / 1000.0, counts_per_s / 1000, 0.05);
}

TEST(EncoderTest, QuadratureDecodingCountsFourTimesAsMany) {
  auto kernel = MakeKernel(RigYaml(0, Drive(", quadrature_x4: true")));
  SetSignal(*kernel, "volts", 6);
  const Tally t = Spin(*kernel, 5000);
  EXPECT_NEAR(static_cast<double>(t.counts), std::round(4 * kCountsPerWheelTurn * t.turns), 1.0);
}

TEST(EncoderTest, EdgeJitterScattersCountsButNeverDrifts) {
  auto kernel = MakeKernel(RigYaml(0, Drive(", jitter_counts_sd: 0.3")));
  SetSignal(*kernel, "volts", 6);
  const Tally t = Spin(*kernel, 50000);
  // the error is one edge offset (sd 0.3 counts) plus the remainder, not a random walk
  EXPECT_NEAR(static_cast<double>(t.counts), kCountsPerWheelTurn * t.turns, 1.0 + 5 * 0.3);
}

TEST(EncoderTest, PeriodLongerThanAStepReportsTheWholeChange) {
  auto kernel = MakeKernel(
      RigYaml(0, Drive().replace(Drive().find("name: e,"), 8, "name: e, period_s: 0.005,")));
  SetSignal(*kernel, "volts", 6);
  const Tally t = Spin(*kernel, 5000, 5);
  EXPECT_NEAR(static_cast<double>(t.counts), std::round(kCountsPerWheelTurn * t.turns), 1.0);
}

}  // namespace
}  // namespace unimouse
