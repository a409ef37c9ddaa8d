// SPDX-License-Identifier: GPL-3.0-or-later
#include "dc_motor.h"

namespace unimouse::plugins {

MotorConstants MotorModel(const std::string& name) {
  // table 3.1 for the 30:1 and 50:1 LP; the others from the original simulator's motor files
  if (name == "pololu_30_1_lp") return {0.079025, 16.66667, 0.001, 0};
  if (name == "pololu_50_1_lp") return {0.1110591, 16.66667, 0.001, 0};
  if (name == "pololu_100_1_lp") return {0.18678114, 16.666666, 0.001, 0};
  if (name == "pololu_150_1_lp") return {0.27014366, 16.216217, 0.001, 0};
  if (name == "pololu_1000_1_lp") return {1.5144416, 18.181818, 0.001, 0};
  if (name == "pololu_30_1_hp") return {0.03494813, 3.75, 0.001, 0};
  throw InputError("unknown motor model '" + name + "'");
}

DcMotor::DcMotor(Params params) : p_(std::move(params)) {
  const char* names[] = {"kt_nm_per_a", "resistance_ohm", "inductance_h", "damping_nm_s_per_rad"};
  if (p_.model == "custom") {
    for (const char* n : names) {
      UNIMOUSE_THROW_UNLESS(
          param::Given(p_.given, n),
          std::string("model 'custom' needs every motor constant; ") + n + " is missing");
    }
  }
  // a named model supplies the constants the robot file does not give
  k_ = p_.model == "custom" ? MotorConstants{} : MotorModel(p_.model);
  if (p_.model == "custom" || param::Given(p_.given, names[0])) k_.kt_nm_per_a = p_.kt_nm_per_a;
  if (p_.model == "custom" || param::Given(p_.given, names[1])) {
    k_.resistance_ohm = p_.resistance_ohm;
  }
  if (p_.model == "custom" || param::Given(p_.given, names[2])) k_.inductance_h = p_.inductance_h;
  if (p_.model == "custom" || param::Given(p_.given, names[3])) {
    k_.damping_nm_s_per_rad = p_.damping_nm_s_per_rad;
  }
}

void DcMotor::Bind(BindContext& ctx) {
  actuator_ = ctx.ActuatorId(p_.actuator);
  voltage_ = ctx.ReadSignal(p_.voltage_in);
  if (!p_.current_out.empty()) current_ = ctx.WriteSignal(p_.current_out);
  dt_s_ = ctx.period_s();
  ctx.SetStateSize(1);  // armature current of the previous step
}

void DcMotor::Reset(const ResetContext& ctx) const {
  ctx.state()[0] = 0;  // eq. 3.14
  if (current_.index >= 0) ctx.Write(current_, 0);
}

void DcMotor::Actuate(const ActuateContext& ctx) const {
  const double wheel_rad_per_s = ctx.data().actuator_velocity[actuator_];
  const double volts = ctx.Read(voltage_);
  const double previous_a = ctx.state()[0];

  // backward difference of eq. 3.1 (eq. 3.13): stable for any L/R, even below one step
  const double back_emf_v = k_.kt_nm_per_a * wheel_rad_per_s;
  const double amps = (k_.inductance_h * previous_a + (volts - back_emf_v) * dt_s_) /
                      (k_.inductance_h + k_.resistance_ohm * dt_s_);

  ctx.state()[0] = amps;
  if (current_.index >= 0) ctx.Write(current_, amps);
  ctx.mutable_data().ctrl[actuator_] =
      k_.kt_nm_per_a * amps - k_.damping_nm_s_per_rad * wheel_rad_per_s;
}

}  // namespace unimouse::plugins
