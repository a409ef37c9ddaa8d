// SPDX-License-Identifier: GPL-3.0-or-later
// The DC motor against closed forms: no-load speed V / Kt, stall current V / Ra, and the
// backward-difference current response of eq. 3.15 on a fixed shaft (table 3.1 constants).
#include <gtest/gtest.h>

#include <cmath>

#include "plugin_rig.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using testing::JointSpeed;
using testing::MakeKernel;
using testing::RigYaml;
using testing::SetSignal;
using testing::SignalValue;

constexpr double kKt = 0.079025;  // table 3.1, Pololu 30:1 LP, at the wheel
constexpr double kRa = 16.66667;
constexpr double kLa = 0.001;

std::string Motor(const std::string& extra = "") {
  return "  - { type: unimouse.dc_motor, name: m, params: { actuator: rotor_motor, voltage_in: "
         "volts, current_out: amps" +
         extra + " } }\n";
}

TEST(DcMotorTest, NoLoadSpeedIsSupplyOverKt) {
  auto kernel = MakeKernel(RigYaml(0, Motor()));
  SetSignal(*kernel, "volts", 6);
  for (int i = 0; i < 1000; ++i) kernel->Step();
  // 6 / 0.079025 = 75.93 rad/s at the wheel: the 725 rpm of the datasheet
  EXPECT_NEAR(JointSpeed(*kernel, "rotor"), 6 / kKt, 0.01 * 6 / kKt);
  EXPECT_NEAR(SignalValue(*kernel, "amps"), 0, 1e-4);
}

TEST(DcMotorTest, ReversedSupplyTurnsTheWheelBackwards) {
  auto kernel = MakeKernel(RigYaml(0, Motor()));
  SetSignal(*kernel, "volts", -3);
  for (int i = 0; i < 1000; ++i) kernel->Step();
  EXPECT_NEAR(JointSpeed(*kernel, "rotor"), -3 / kKt, 0.01 * 3 / kKt);
}

TEST(DcMotorTest, StallCurrentIsSupplyOverResistance) {
  // an enormous armature holds the shaft still: torque 0.03 N m barely moves 1e6 kg m^2
  auto kernel = MakeKernel(RigYaml(1e6, Motor()));
  SetSignal(*kernel, "volts", 6);
  for (int i = 0; i < 20; ++i) kernel->Step();
  EXPECT_NEAR(SignalValue(*kernel, "amps"), 6 / kRa, 0.01 * 6 / kRa);  // 0.36 A
}

TEST(DcMotorTest, CurrentStepResponseFollowsTheBackwardDifferenceExactly) {
  auto kernel = MakeKernel(RigYaml(1e6, Motor()));
  SetSignal(*kernel, "volts", 6);
  // eq. 3.15 with w = 0 and i(0) = 0 (eq. 3.14): i_k = a i_(k-1) + b, so i_k = (V/R)(1 - a^k)
  const double dt = 0.001;
  const double a = kLa / (kLa + kRa * dt);
  for (int k = 1; k <= 10; ++k) {
    kernel->Step();
    const double expected = 6 / kRa * (1 - std::pow(a, k));
    EXPECT_NEAR(SignalValue(*kernel, "amps"), expected, 1e-9) << "step " << k;
  }
}

TEST(DcMotorTest, DampingLowersTheNoLoadSpeed) {
  // steady state: Kt (V - Kt w) / R = lambda w, so w = Kt V / (Kt^2 + lambda R)
  const double lambda = 1e-4;
  auto kernel = MakeKernel(RigYaml(0, Motor(", damping_nm_s_per_rad: 0.0001")));
  SetSignal(*kernel, "volts", 6);
  for (int i = 0; i < 2000; ++i) kernel->Step();
  const double expected = kKt * 6 / (kKt * kKt + lambda * kRa);
  EXPECT_NEAR(JointSpeed(*kernel, "rotor"), expected, 0.01 * expected);
}

TEST(DcMotorTest, ModelChoosesTheConstantsOfTable31) {
  auto kernel = MakeKernel(RigYaml(0, Motor(", model: pololu_50_1_lp")));
  SetSignal(*kernel, "volts", 6);
  for (int i = 0; i < 2000; ++i) kernel->Step();
  EXPECT_NEAR(JointSpeed(*kernel, "rotor"), 6 / 0.1110591, 0.01 * 6 / 0.1110591);
}

TEST(DcMotorTest, GivenConstantsOverrideTheModel) {
  auto kernel = MakeKernel(RigYaml(0, Motor(", kt_nm_per_a: 0.05")));
  SetSignal(*kernel, "volts", 6);
  for (int i = 0; i < 2000; ++i) kernel->Step();
  EXPECT_NEAR(JointSpeed(*kernel, "rotor"), 6 / 0.05, 0.01 * 6 / 0.05);
}

TEST(DcMotorTest, CustomModelNeedsEveryConstant) {
  try {
    MakeKernel(RigYaml(0, Motor(", model: custom, kt_nm_per_a: 0.05")));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model 'custom' needs every motor constant; "
                                         "resistance_ohm is missing"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace unimouse
