// SPDX-License-Identifier: GPL-3.0-or-later
// Brushed DC motor with gearbox (dissertation section 3.2.1). The armature current follows
// eq. 3.1 discretised by a backward difference (eq. 3.11-3.14):
//
//   i_t = (L i_{t-1} + V dt - Kt w dt) / (L + R dt)
//
// which is eq. 3.15 with the dt on the back-EMF term that eq. 3.13 implies (eq. 3.15 as printed
// omits it; the original simulator's code has it). The wheel receives T = Kt i - lambda w
// (eq. 3.7-3.10) through its MuJoCo actuator; MuJoCo applies the reaction to the chassis.
//
// Every parameter refers to the gearbox output shaft, the wheel: w is the wheel's angular speed
// and Kt the torque per ampere at the wheel. The gear ratio only matters to an encoder on the
// motor shaft, so the encoder has its own gear_ratio.
#ifndef UNIMOUSE_PLUGINS_DC_MOTOR_H_
#define UNIMOUSE_PLUGINS_DC_MOTOR_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

/// Motor constants at the wheel shaft.
struct MotorConstants {
  double kt_nm_per_a;
  double resistance_ohm;
  double inductance_h;
  double damping_nm_s_per_rad;
};

/// Returns the constants of a named model (table 3.1, and the original simulator's other Pololu
/// micro metal gearmotor files, all at 6 V); throws InputError for an unknown name.
MotorConstants MotorModel(const std::string& name);

struct DcMotorParams {
  std::string actuator;
  std::string voltage_in;
  std::string current_out;
  std::string model = "pololu_30_1_lp";
  double kt_nm_per_a = 0.079025;
  double resistance_ohm = 16.66667;
  double inductance_h = 0.001;
  double damping_nm_s_per_rad = 0;
  param::GivenSet given;

  template <class V>
  void Visit(V& v) {
    v("actuator", actuator, "MuJoCo actuator on the wheel hinge it drives", param::Required{});
    v("voltage_in", voltage_in, "signal it reads: armature voltage, volts", param::Required{});
    v("current_out", current_out, "signal it writes: armature current, amperes");
    v("model", model, "motor whose constants are the defaults; custom: give all four",
      param::OneOf{"pololu_30_1_lp|pololu_50_1_lp|pololu_100_1_lp|pololu_150_1_lp|"
                   "pololu_1000_1_lp|pololu_30_1_hp|custom"});
    v("kt_nm_per_a", kt_nm_per_a, "torque constant at the wheel, = back-EMF constant (eq. 3.6)",
      param::Positive{});
    v("resistance_ohm", resistance_ohm, "armature resistance Ra", param::Positive{});
    v("inductance_h", inductance_h, "armature inductance La", param::NonNegative{});
    v("damping_nm_s_per_rad", damping_nm_s_per_rad, "viscous damping lambda at the wheel",
      param::NonNegative{});
  }
};

class DcMotor final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.dc_motor";
  static constexpr const char* kSummary = "brushed DC gearmotor: armature current eq. 3.13-3.15";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = DcMotorParams;

  explicit DcMotor(Params params);
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Actuate(const ActuateContext& ctx) const override;

  const MotorConstants& constants() const { return k_; }

 private:
  const Params p_;
  MotorConstants k_;
  int actuator_ = -1;
  double dt_s_ = 0;
  SignalId voltage_, current_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_DC_MOTOR_H_
