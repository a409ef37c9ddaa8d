// SPDX-License-Identifier: GPL-3.0-or-later
// The suction fan on the gyro robot: the downforce follows its command first-order to
// F_max (d V / V_rated)^2, the floor then carries the robot's weight plus the downforce, and
// the battery sags by the fan's current times its internal resistance.
#include <gtest/gtest.h>

#include <cmath>

#include "inline_assets.h"
#include "plugin_rig.h"

namespace unimouse {
namespace {

using testing::GyroRobotWith;
using testing::MakeKernel;
using testing::SetSignal;
using testing::SignalValue;

std::string FanWith(const std::string& params) {
  return "  - { type: unimouse.fan, name: fan,\n"
         "      params: { command_in: fan.command, downforce_out: fan.downforce_n, "
         "current_out: fan.current_a, max_downforce_n: 1.5, time_constant_s: 0.05" +
         params + " } }\n";
}

// the sum of the normal forces of every contact of the robot with the floor, newtons
double FloorLoad_n(const Kernel& kernel) {
  const mjModel& m = kernel.mj_model();
  const mjData& d = kernel.state().data();
  double load = 0;
  for (int i = 0; i < d.ncon; ++i) {
    mjtNum force[6];
    mj_contactForce(&m, &d, i, force);
    load += force[0];
  }
  return load;
}

TEST(FanTest, DownforceRisesFirstOrderToItsMaximumAtFullDuty) {
  auto kernel = MakeKernel(GyroRobotWith(FanWith("")));
  SetSignal(*kernel, "fan.command", 1023);
  // one time constant: 1 - 1/e of the way
  for (int i = 0; i < 50; ++i) kernel->Step();
  EXPECT_NEAR(SignalValue(*kernel, "fan.downforce_n"), 1.5 * (1 - std::exp(-1.0)), 0.01 * 1.5);
  for (int i = 0; i < 450; ++i) kernel->Step();
  EXPECT_NEAR(SignalValue(*kernel, "fan.downforce_n"), 1.5, 0.001 * 1.5);
  EXPECT_NEAR(SignalValue(*kernel, "fan.current_a"), 1.0, 0.001);
}

TEST(FanTest, HalfDutyGivesAQuarterOfTheDownforce) {
  auto kernel = MakeKernel(GyroRobotWith(FanWith("")));
  SetSignal(*kernel, "fan.command", 1023 / 2.0);
  for (int i = 0; i < 1000; ++i) kernel->Step();
  EXPECT_NEAR(SignalValue(*kernel, "fan.downforce_n"), 1.5 / 4, 1e-6);
}

TEST(FanTest, TheFloorCarriesTheWeightPlusTheDownforce) {
  auto kernel = MakeKernel(GyroRobotWith(FanWith("")));
  const double weight_n = mj_getTotalmass(&kernel->mj_model()) * 9.81;
  for (int i = 0; i < 500; ++i) kernel->Step();
  EXPECT_NEAR(FloorLoad_n(*kernel), weight_n, 0.01 * weight_n);
  SetSignal(*kernel, "fan.command", 1023);
  for (int i = 0; i < 1000; ++i) kernel->Step();
  EXPECT_NEAR(FloorLoad_n(*kernel), weight_n + 1.5, 0.01 * (weight_n + 1.5));
}

TEST(FanTest, TheBatterySagsUnderTheFanAndTheFanSlowsWithIt) {
  // E = 6 V, R = 0.5 ohm, fan alone: V = E - R I and I = I_max (V / E)^2 at full duty, so
  // 0.5 V^2 / 36 + V - 6 = 0
  auto kernel = MakeKernel(GyroRobotWith(
      "  - { type: unimouse.battery, name: pack,\n"
      "      params: { emf_v: 6, internal_resistance_ohm: 0.5, voltage_out: pack.voltage_v,\n"
      "                load_currents: fan.current_a } }\n" +
      FanWith(", voltage_in: pack.voltage_v")));
  SetSignal(*kernel, "fan.command", 1023);
  for (int i = 0; i < 2000; ++i) kernel->Step();
  const double a = 0.5 / 36, volts = (-1 + std::sqrt(1 + 4 * a * 6)) / (2 * a);
  EXPECT_NEAR(SignalValue(*kernel, "pack.voltage_v"), volts, 1e-3);
  EXPECT_NEAR(SignalValue(*kernel, "fan.current_a"), (6 - volts) / 0.5, 1e-3);
  EXPECT_NEAR(SignalValue(*kernel, "fan.downforce_n"), 1.5 * (volts / 6) * (volts / 6), 1e-3);
}

TEST(FanTest, ANegativeCommandLeavesTheFanOff) {
  auto kernel = MakeKernel(GyroRobotWith(FanWith("")));
  SetSignal(*kernel, "fan.command", -1023);
  for (int i = 0; i < 200; ++i) kernel->Step();
  EXPECT_EQ(SignalValue(*kernel, "fan.downforce_n"), 0);
}

}  // namespace
}  // namespace unimouse
