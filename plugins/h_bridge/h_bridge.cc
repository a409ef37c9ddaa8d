// SPDX-License-Identifier: GPL-3.0-or-later
#include "h_bridge.h"

#include <algorithm>

namespace unimouse::plugins {

HBridge::HBridge(Params params)
    : p_(std::move(params)), full_scale_((1 << p_.resolution_bits) - 1) {
  UNIMOUSE_THROW_UNLESS(p_.motor_current_in.empty() == p_.supply_current_out.empty(),
                        "motor_current_in and supply_current_out go together");
}

void HBridge::Bind(BindContext& ctx) {
  command_ = ctx.ReadSignal(p_.command_in);
  supply_ = ctx.ReadSignal(p_.supply_in);
  voltage_ = ctx.WriteSignal(p_.voltage_out);
  if (!p_.motor_current_in.empty()) {
    motor_current_ = ctx.ReadSignal(p_.motor_current_in);
    supply_current_ = ctx.WriteSignal(p_.supply_current_out);
  }
}

double HBridge::DutyCycle(double command) const {
  if (p_.mode == "locked_antiphase") {
    // table 3.4: 0 full reverse, half scale stop, full scale full forward
    return 2 * std::clamp(command, 0.0, full_scale_) / full_scale_ - 1;
  }
  return std::clamp(command, -full_scale_, full_scale_) / full_scale_;
}

void HBridge::Actuate(const ActuateContext& ctx) const {
  const double duty = DutyCycle(ctx.Read(command_));
  ctx.Write(voltage_, duty * ctx.Read(supply_));

  // an ideal switch passes power through: V_in I_in = V_out I_out
  if (supply_current_.index >= 0) ctx.Write(supply_current_, duty * ctx.Read(motor_current_));
}

}  // namespace unimouse::plugins
