// SPDX-License-Identifier: GPL-3.0-or-later
// The H-bridge reproduces tables 3.3 (sign-magnitude) and 3.4 (locked anti-phase) through
// V_out = D V_in (eq. 3.16), with out-of-range commands clamped.
#include <gtest/gtest.h>

#include "plugin_rig.h"

namespace unimouse {
namespace {

using testing::MakeKernel;
using testing::RigYaml;
using testing::SetSignal;
using testing::SignalValue;

class HBridgeTest : public ::testing::Test {
 protected:
  // battery 6 V -> bridge -> measured output voltage, for one command
  double OutputFor(double command, const std::string& mode = "sign_magnitude") {
    auto kernel = MakeKernel(
        RigYaml(0,
                "  - { type: unimouse.battery, name: b, params: { emf_v: 6 } }\n"
                "  - { type: unimouse.h_bridge, name: h, params: { command_in: volts, voltage_out: "
                "out, mode: " +
                    mode + " } }\n"));
    SetSignal(*kernel, "volts", command);
    kernel->Step();
    return SignalValue(*kernel, "out");
  }
};

TEST_F(HBridgeTest, SignMagnitudeRowsOfTable33) {
  // sign 1: 100 % forward full speed, 50 % half speed, 0 % brake (terminals shorted, 0 V)
  EXPECT_DOUBLE_EQ(OutputFor(1023), 6.0);
  EXPECT_DOUBLE_EQ(OutputFor(511.5), 3.0);
  EXPECT_DOUBLE_EQ(OutputFor(0), 0.0);
  // sign 0: 50 % backward half speed, 100 % backward full speed
  EXPECT_DOUBLE_EQ(OutputFor(-511.5), -3.0);
  EXPECT_DOUBLE_EQ(OutputFor(-1023), -6.0);
}

TEST_F(HBridgeTest, OutOfRangeCommandsAreClamped) {
  EXPECT_DOUBLE_EQ(OutputFor(1024), 6.0);
  EXPECT_DOUBLE_EQ(OutputFor(40000), 6.0);
  EXPECT_DOUBLE_EQ(OutputFor(-32768), -6.0);
}

TEST_F(HBridgeTest, LockedAntiPhaseRowsOfTable34) {
  const std::string lap = "locked_antiphase";
  EXPECT_DOUBLE_EQ(OutputFor(1023, lap), 6.0);     // 100 %: forward full speed
  EXPECT_DOUBLE_EQ(OutputFor(767.25, lap), 3.0);   // 75 %: forward half speed
  EXPECT_DOUBLE_EQ(OutputFor(511.5, lap), 0.0);    // 50 %: stop
  EXPECT_DOUBLE_EQ(OutputFor(255.75, lap), -3.0);  // 25 %: backward half speed
  EXPECT_DOUBLE_EQ(OutputFor(0, lap), -6.0);       // 0 %: backward full speed
  EXPECT_DOUBLE_EQ(OutputFor(-100, lap), -6.0);    // clamped
}

TEST_F(HBridgeTest, FollowsTheSupplyVoltage) {
  auto kernel = MakeKernel(RigYaml(
      0,
      "  - { type: unimouse.battery, name: b, params: { emf_v: 7.4 } }\n"
      "  - { type: unimouse.h_bridge, name: h, params: { command_in: volts, voltage_out: out } "
      "}\n"));
  SetSignal(*kernel, "volts", 511.5);
  kernel->Step();
  EXPECT_DOUBLE_EQ(SignalValue(*kernel, "out"), 3.7);
}

TEST(BatteryTest, InternalResistanceDropsTheVoltageByTheLoadCurrent) {
  // two motors behind bridges draw from one battery of 1 ohm; V = E - I R with last tick's I
  auto kernel = MakeKernel(RigYaml(
      1e6,
      "  - { type: unimouse.battery, name: b, params: { emf_v: 6, internal_resistance_ohm: 1, "
      "load_currents: supply_a } }\n"
      "  - { type: unimouse.h_bridge, name: h, params: { command_in: volts, voltage_out: out, "
      "motor_current_in: amps, supply_current_out: supply_a } }\n"
      "  - { type: unimouse.dc_motor, name: m, params: { actuator: rotor_motor, voltage_in: out, "
      "current_out: amps } }\n"));
  SetSignal(*kernel, "volts", 1023);
  for (int i = 0; i < 50; ++i) kernel->Step();
  // a stalled motor: I = V / Ra and V = E - I * 1, so V = E Ra / (Ra + 1)
  const double ra = 16.66667;
  EXPECT_NEAR(SignalValue(*kernel, "battery.voltage_v"), 6 * ra / (ra + 1), 1e-6);
  EXPECT_NEAR(SignalValue(*kernel, "amps"), 6 / (ra + 1), 1e-6);
}

}  // namespace
}  // namespace unimouse
