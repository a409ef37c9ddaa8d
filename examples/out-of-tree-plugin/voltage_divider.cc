// SPDX-License-Identifier: GPL-3.0-or-later
// An example component: the resistor divider that brings the battery's voltage down to an ADC
// pin, V_out = V_in R_bottom / (R_top + R_bottom). In a robot file:
//
//   - type: lab.voltage_divider
//     name: battery_monitor
//     params: {top_ohm: 10000, bottom_ohm: 4700}
#include <string>

#include "unimouse/component.h"

namespace lab {

struct VoltageDividerParams {
  double top_ohm = 10000;
  double bottom_ohm = 10000;
  std::string voltage_in = "battery.voltage_v";
  std::string voltage_out = "battery_monitor.voltage_v";

  template <class V>
  void Visit(V& v) {
    v("top_ohm", top_ohm, "resistor between the input and the output", unimouse::param::Positive{});
    v("bottom_ohm", bottom_ohm, "resistor between the output and ground",
      unimouse::param::Positive{});
    v("voltage_in", voltage_in, "signal it reads: the voltage to divide, volts");
    v("voltage_out", voltage_out, "signal it writes: the voltage at the ADC pin, volts");
  }
};

class VoltageDivider final : public unimouse::Component {
 public:
  static constexpr const char* kTypeName = "lab.voltage_divider";
  static constexpr const char* kSummary =
      "resistor divider: V_out = V_in R_bottom / (R_top + R_bottom)";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = VoltageDividerParams;

  explicit VoltageDivider(Params params) : p_(std::move(params)) {}

  void Bind(unimouse::BindContext& ctx) override {
    in_ = ctx.ReadSignal(p_.voltage_in);
    out_ = ctx.WriteSignal(p_.voltage_out);
  }

  void Sense(const unimouse::SenseContext& ctx) const override {
    ctx.Write(out_, ctx.Read(in_) * p_.bottom_ohm / (p_.top_ohm + p_.bottom_ohm));
  }

 private:
  const Params p_;
  unimouse::SignalId in_;
  unimouse::SignalId out_;
};

}  // namespace lab

UNIMOUSE_EXPORT_PLUGIN(lab::VoltageDivider)
