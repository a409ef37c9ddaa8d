// SPDX-License-Identifier: GPL-3.0-or-later
// Battery (dissertation section 3.2, table 4.4): an ideal source by default, with an optional
// internal resistance, V = E - I R, where I is the total current its loads drew on the previous
// tick.
#ifndef UNIMOUSE_PLUGINS_BATTERY_H_
#define UNIMOUSE_PLUGINS_BATTERY_H_

#include <string>
#include <vector>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct BatteryParams {
  double emf_v = 6.0;
  double internal_resistance_ohm = 0;
  std::string voltage_out = "battery.voltage_v";
  std::string load_currents;

  template <class V>
  void Visit(V& v) {
    v("emf_v", emf_v, "open-circuit voltage", param::Positive{});
    v("internal_resistance_ohm", internal_resistance_ohm,
      "internal resistance; 0 is an ideal source", param::NonNegative{});
    v("voltage_out", voltage_out, "signal it writes: terminal voltage, volts");
    v("load_currents", load_currents,
      "comma-separated signals of the currents drawn from it, amperes");
  }
};

class Battery final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.battery";
  static constexpr const char* kSummary = "battery: ideal source or V = E - I R";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = BatteryParams;

  explicit Battery(Params params) : p_(std::move(params)) {}
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Actuate(const ActuateContext& ctx) const override;

 private:
  const Params p_;
  SignalId voltage_;
  std::vector<SignalId> loads_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_BATTERY_H_
