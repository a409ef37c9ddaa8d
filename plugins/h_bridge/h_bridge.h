// SPDX-License-Identifier: GPL-3.0-or-later
// H-bridge (dissertation section 3.2.2): an average-voltage model, V_out = D * V_in (eq. 3.16).
// Sign-magnitude drive (table 3.3): the command is a signed duty cycle of `resolution_bits`
// magnitude bits plus a sign, clamped to [-full, full]; 0 shorts the motor (brake). Locked
// anti-phase (table 3.4): the command is a duty cycle in [0, full], 50 % stops the motor.
#ifndef UNIMOUSE_PLUGINS_H_BRIDGE_H_
#define UNIMOUSE_PLUGINS_H_BRIDGE_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct HBridgeParams {
  std::string command_in;
  std::string supply_in = "battery.voltage_v";
  std::string voltage_out;
  std::string mode = "sign_magnitude";
  int resolution_bits = 10;
  std::string motor_current_in;
  std::string supply_current_out;

  template <class V>
  void Visit(V& v) {
    v("command_in", command_in, "signal it reads: the duty-cycle command", param::Required{});
    v("supply_in", supply_in, "signal it reads: supply voltage, volts");
    v("voltage_out", voltage_out, "signal it writes: voltage across the motor, volts",
      param::Required{});
    v("mode", mode, "drive mode (tables 3.3 and 3.4)",
      param::OneOf{"sign_magnitude|locked_antiphase"});
    v("resolution_bits", resolution_bits, "bits of duty-cycle magnitude; full scale 2^bits - 1",
      param::Range{1, 16});
    v("motor_current_in", motor_current_in,
      "signal it reads: motor current, amperes; with supply_current_out, for a battery's load");
    v("supply_current_out", supply_current_out,
      "signal it writes: current drawn from the supply, D times the motor current, amperes");
  }
};

class HBridge final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.h_bridge";
  static constexpr const char* kSummary = "H-bridge: V_out = D V_in (eq. 3.16, tables 3.3/3.4)";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = HBridgeParams;

  explicit HBridge(Params params);
  void Bind(BindContext& ctx) override;
  void Actuate(const ActuateContext& ctx) const override;

  /// Returns the duty cycle D in [-1, 1] for a command, after clamping.
  double DutyCycle(double command) const;

 private:
  const Params p_;
  const double full_scale_;
  SignalId command_, supply_, voltage_, motor_current_, supply_current_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_H_BRIDGE_H_
