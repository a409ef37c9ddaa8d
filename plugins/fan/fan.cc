// SPDX-License-Identifier: GPL-3.0-or-later
#include "fan.h"

#include <algorithm>
#include <cmath>

namespace unimouse::plugins {
namespace {

// state slots: the downforce now, and the part of the body's applied z force that is the fan's
constexpr int kDownforce = 0;
constexpr int kApplied = 1;

}  // namespace

void Fan::Bind(BindContext& ctx) {
  body_ = ctx.BodyId(p_.body);
  command_ = ctx.ReadSignal(p_.command_in);
  if (!p_.voltage_in.empty()) voltage_ = ctx.ReadSignal(p_.voltage_in);
  if (!p_.downforce_out.empty()) downforce_ = ctx.WriteSignal(p_.downforce_out);
  if (!p_.current_out.empty()) current_ = ctx.WriteSignal(p_.current_out);
  decay_ = std::exp(-ctx.period_s() / p_.time_constant_s);
  ctx.SetStateSize(2);
}

void Fan::Reset(const ResetContext& ctx) const {
  ctx.state()[kDownforce] = 0;
  ctx.state()[kApplied] = 0;
  if (downforce_.index >= 0) ctx.Write(downforce_, 0);
  if (current_.index >= 0) ctx.Write(current_, 0);
}

void Fan::Actuate(const ActuateContext& ctx) const {
  std::span<double> s = ctx.state();
  const double duty = std::clamp(ctx.Read(command_) / p_.command_full_scale, 0.0, 1.0);
  const double volts = voltage_.index >= 0 ? std::max(0.0, ctx.Read(voltage_)) : p_.rated_voltage_v;
  const double speed = duty * volts / p_.rated_voltage_v;
  const double target_n = p_.max_downforce_n * speed * speed;
  const double force_n = target_n + (s[kDownforce] - target_n) * decay_;
  s[kDownforce] = force_n;

  // xfrc_applied persists between steps and others may push the same body: change only the
  // fan's own share of it
  mjData& d = ctx.mutable_data();
  d.xfrc_applied[6 * body_ + 2] += -force_n - s[kApplied];
  s[kApplied] = -force_n;

  if (downforce_.index >= 0) ctx.Write(downforce_, force_n);
  if (current_.index >= 0) {
    const double share = p_.max_downforce_n > 0 ? force_n / p_.max_downforce_n : 0;
    ctx.Write(current_, p_.max_current_a * share);
  }
}

}  // namespace unimouse::plugins
