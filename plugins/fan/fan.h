// SPDX-License-Identifier: GPL-3.0-or-later
// A suction fan under the chassis. Its command (a PWM duty, as a signed H-bridge-style command
// out of `command_full_scale`) and the supply voltage set a target downforce
//
//   F* = F_max (d V / V_rated)^2,  d = clamp(command / command_full_scale, 0, 1)
//
// (thrust goes with the square of the impeller's speed, and the speed with the applied voltage);
// the downforce follows it first-order, F <- F + (F* - F)(1 - exp(-dt / tau)), and the current
// drawn goes with the downforce, I = I_max F / F_max (the impeller's drag torque also goes with
// the square of its speed). The world receives F as a force pushing the body down, through
// mjData.xfrc_applied at the body's centre of mass.
#ifndef UNIMOUSE_PLUGINS_FAN_H_
#define UNIMOUSE_PLUGINS_FAN_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct FanParams {
  std::string body = "chassis";
  std::string command_in;
  double command_full_scale = 1023;
  std::string voltage_in;
  double rated_voltage_v = 6;
  double max_downforce_n = 1.0;
  double time_constant_s = 0.1;
  double max_current_a = 1.0;
  std::string downforce_out;
  std::string current_out;

  template <class V>
  void Visit(V& v) {
    v("body", body, "robot body the downforce acts on, at its centre of mass");
    v("command_in", command_in, "signal it reads: the fan's PWM command", param::Required{});
    v("command_full_scale", command_full_scale, "command that is 100 % duty; below 0 is off",
      param::Positive{});
    v("voltage_in", voltage_in,
      "signal it reads: supply voltage, volts; empty: always rated_voltage_v");
    v("rated_voltage_v", rated_voltage_v, "supply voltage at which full duty gives max_downforce_n",
      param::Positive{});
    v("max_downforce_n", max_downforce_n, "steady downforce at full duty and rated voltage",
      param::NonNegative{});
    v("time_constant_s", time_constant_s, "first-order time constant of the downforce",
      param::Positive{});
    v("max_current_a", max_current_a, "current drawn at max_downforce_n", param::NonNegative{});
    v("downforce_out", downforce_out, "signal it writes: the downforce, newtons");
    v("current_out", current_out, "signal it writes: the current drawn, amperes (for a battery)");
  }
};

class Fan final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.fan";
  static constexpr const char* kSummary =
      "suction fan: PWM to downforce, first-order, current from the battery";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = FanParams;

  explicit Fan(Params params) : p_(std::move(params)) {}
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Actuate(const ActuateContext& ctx) const override;

 private:
  const Params p_;
  int body_ = -1;
  double decay_ = 0;
  SignalId command_, voltage_, downforce_, current_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_FAN_H_
