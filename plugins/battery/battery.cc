// SPDX-License-Identifier: GPL-3.0-or-later
#include "battery.h"

namespace unimouse::plugins {

void Battery::Bind(BindContext& ctx) {
  voltage_ = ctx.WriteSignal(p_.voltage_out);
  for (const auto& load : param::SplitList(p_.load_currents))
    loads_.push_back(ctx.ReadSignal(load));
}

void Battery::Reset(const ResetContext& ctx) const { ctx.Write(voltage_, p_.emf_v); }

void Battery::Actuate(const ActuateContext& ctx) const {
  double current_a = 0;
  for (SignalId load : loads_) current_a += ctx.Read(load);
  ctx.Write(voltage_, p_.emf_v - current_a * p_.internal_resistance_ohm);
}

}  // namespace unimouse::plugins
