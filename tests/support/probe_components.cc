// SPDX-License-Identifier: GPL-3.0-or-later
#include "probe_components.h"

namespace unimouse::testing {

std::vector<std::string>& ProbeEvents() {
  static std::vector<std::string> events;
  return events;
}

void Probe::Bind(BindContext& ctx) {
  actuator_ = ctx.ActuatorId("left_motor");
  chassis_ = ctx.BodyId("chassis");
  ctx.SetStateSize(1);
}

void Probe::Reset(const ResetContext& ctx) const {
  ctx.state()[0] = 0;
  ProbeEvents().push_back("reset:" + p_.tag);
}

void Probe::Sense(const SenseContext& ctx) const {
  ctx.state()[0] += 1;
  ProbeEvents().push_back("sense:" + p_.tag);
  ProbeEvents().push_back("x=" + std::to_string(ctx.data().xpos[3 * chassis_]));
}

void Probe::Actuate(const ActuateContext& ctx) const {
  ProbeEvents().push_back("actuate:" + p_.tag);
  if (p_.torque_nm != 0) ctx.mutable_data().ctrl[actuator_] = p_.torque_nm;
}

void RandomTorque::Bind(BindContext& ctx) {
  left_ = ctx.ActuatorId("left_motor");
  right_ = ctx.ActuatorId("right_motor");
  rng_ = ctx.Rng("drive.noise");
}

void RandomTorque::Actuate(const ActuateContext& ctx) const {
  ctx.mutable_data().ctrl[left_] = p_.scale_nm * ctx.Normal(rng_);
  ctx.mutable_data().ctrl[right_] = p_.scale_nm * ctx.Normal(rng_);
}

void SignalRelay::Bind(BindContext& ctx) {
  if (!p_.read.empty()) in_ = ctx.ReadSignal(p_.read);
  if (!p_.write.empty()) out_ = ctx.WriteSignal(p_.write);
}

void SignalRelay::Actuate(const ActuateContext& ctx) const {
  if (out_.index >= 0) ctx.Write(out_, (in_.index >= 0 ? ctx.Read(in_) : 0) + 1);
}

void MujocoError::Actuate(const ActuateContext& ctx) const {
  if (ctx.step() != p_.at_step) return;
  mjData& d = ctx.mutable_data();
  const int free = d.nstack - d.pstack;
  mj_stackAlloc(&d, p_.where == "hook" ? free + 1 : free - 1);
}

void Gyro::Bind(BindContext& ctx) {
  body_ = ctx.BodyId(p_.body);
  rate_ = ctx.WriteSignal(p_.rate_out);
}

void Gyro::Sense(const SenseContext& ctx) const {
  // cvel holds the rotation first, in world axes: its z is the yaw rate
  ctx.Write(rate_, ctx.data().cvel[6 * body_ + 2]);
}

}  // namespace unimouse::testing
