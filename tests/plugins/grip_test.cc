// SPDX-License-Identifier: GPL-3.0-or-later
// Grip and slip of the gyro robot on MuJoCo 2.2.2's contact model, measured (docs/robots.md,
// "Grip and slip"): the speed at which a steady turn slides out against the Coulomb limit
// sqrt(mu (m g + F_down) r / m), with and without the fan, and the wheel spin of a start at full
// command, which the motors' stall force (1.78 N a wheel) against about 0.25 N of traction
// makes traction-limited: the chassis accelerates at mu N_wheels / m.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "inline_assets.h"
#include "plugin_rig.h"

namespace unimouse {
namespace {

using testing::GyroRobotWith;
using testing::JointSpeed;
using testing::MakeKernel;
using testing::SetSignal;
using testing::SignalValue;

constexpr double kMu =
    0.35;  // the wheels' friction (the floor's 0.1 is lower; MuJoCo takes the larger)
constexpr double kWheelRadius_m = 0.016;
constexpr double kHalfTrack_m = 0.048;

std::string Fan(double max_downforce_n) {
  char text[200];
  std::snprintf(text, sizeof(text),
                "  - { type: unimouse.fan, name: fan,\n"
                "      params: { command_in: fan.command, max_downforce_n: %g } }\n",
                max_downforce_n);
  return text;
}

// the chassis's velocity in its own frame (forward, left) and its yaw rate
struct Motion {
  double forward_m_s, left_m_s, yaw_rate_rad_s;
};
Motion ChassisMotion(const Kernel& kernel) {
  const mjData& d = kernel.state().data();
  // the free joint's linear velocity is in world axes, its angular velocity in the body's
  const double yaw = kernel.world().RobotPose(d).yaw_rad;
  return {d.qvel[0] * std::cos(yaw) + d.qvel[1] * std::sin(yaw),
          -d.qvel[0] * std::sin(yaw) + d.qvel[1] * std::cos(yaw), d.qvel[5]};
}

// the normal load the wheels carry at rest, with downforce F at the chassis's centre of mass:
// moments about the axle put the rest on the caster
double WheelLoad_n(const Kernel& kernel, double downforce_n) {
  const mjModel& m = kernel.mj_model();
  const mjData& d = kernel.state().data();
  const int chassis = mj_name2id(&m, mjOBJ_BODY, "chassis");
  const int caster = mj_name2id(&m, mjOBJ_BODY, "caster");
  const double* frame = d.xmat + 9 * chassis;  // column 0: the chassis's x axis
  auto ahead_m = [&](const double* p) {
    return (p[0] - d.xpos[3 * chassis]) * frame[0] + (p[1] - d.xpos[3 * chassis + 1]) * frame[3];
  };
  const double weight_n = mj_getTotalmass(&m) * 9.81;
  const double caster_behind_m = -ahead_m(d.xpos + 3 * caster);
  const double on_caster_n = (weight_n * -ahead_m(d.subtree_com + 3 * chassis) +
                              downforce_n * -ahead_m(d.xipos + 3 * chassis)) /
                             caster_behind_m;
  return weight_n + downforce_n - on_caster_n;
}

struct SlideOut {
  double radius_m;                 // the turn's radius when it slid
  double speed_m_s;                // the speed then
  double predicted_m_s;            // sqrt(mu (m g + F) r / m)
  double wheels_only_m_s;          // the same with the wheels' share of the load only
  double slip_angle_rad_per_m_s2;  // sideslip at the axle per unit of lateral acceleration
};

// turns left at a fixed ratio of wheel commands (a turn of about one cell's radius), raising
// the commands slowly; it slides when its lateral acceleration v w stops growing
SlideOut MeasureSlideOut(double downforce_n, bool elliptic_cones = false) {
  auto kernel = MakeKernel(GyroRobotWith(Fan(downforce_n)));
  // an experiment, not a robot file's option: the world builds pyramidal cones (MuJoCo's
  // default), and the model is switched to elliptic ones after it is built
  if (elliptic_cones) const_cast<mjModel&>(kernel->mj_model()).opt.cone = mjCONE_ELLIPTIC;
  const double mass_kg = mj_getTotalmass(&kernel->mj_model());
  SetSignal(*kernel, "fan.command", 1023);
  for (int i = 0; i < 1000; ++i) kernel->Step();
  const double wheel_load_n = WheelLoad_n(*kernel, downforce_n);
  const double ratio = (0.18 - kHalfTrack_m) / (0.18 + kHalfTrack_m);
  SlideOut out{};
  double best = 0, slope_num = 0, slope_den = 0;
  const int window = 100;
  double a_sum = 0, v_sum = 0, w_sum = 0, side_sum = 0;
  for (int i = 0; i < 20000; ++i) {
    const double command = 150 + 873.0 * i / 20000;
    SetSignal(*kernel, "left.command", ratio * command);
    SetSignal(*kernel, "right.command", command);
    kernel->Step();
    const Motion m = ChassisMotion(*kernel);
    a_sum += m.forward_m_s * m.yaw_rate_rad_s;
    v_sum += m.forward_m_s;
    w_sum += m.yaw_rate_rad_s;
    side_sum += std::atan2(-m.left_m_s, m.forward_m_s);
    if ((i + 1) % window != 0) continue;
    const double a = a_sum / window, v = v_sum / window, w = w_sum / window;
    const double beta = side_sum / window;
    if (a > best) {
      best = a;
      out.radius_m = v / w;
      out.speed_m_s = v;
    }
    // the slip angle while it still grips (below half the limit), fitted through the origin
    if (a < 0.5 * kMu * 9.81) {
      slope_num += a * beta;
      slope_den += a * a;
    }
    a_sum = v_sum = w_sum = side_sum = 0;
  }
  out.predicted_m_s = std::sqrt(kMu * (mass_kg * 9.81 + downforce_n) * out.radius_m / mass_kg);
  out.wheels_only_m_s = std::sqrt(kMu * wheel_load_n * out.radius_m / mass_kg);
  out.slip_angle_rad_per_m_s2 = slope_den > 0 ? slope_num / slope_den : 0;
  std::printf(
      "%s, downforce %.2f N: slid at %.3f m/s on r = %.3f m (a = %.2f m/s^2); Coulomb %.3f m/s, "
      "wheels' share only %.3f m/s; slip angle %.4f rad per m/s^2\n",
      elliptic_cones ? "elliptic" : "pyramidal", downforce_n, out.speed_m_s, out.radius_m,
      out.speed_m_s * out.speed_m_s / out.radius_m, out.predicted_m_s, out.wheels_only_m_s,
      out.slip_angle_rad_per_m_s2);
  return out;
}

// MuJoCo's default pyramidal friction cone (condim 3) holds mu N along the two axes of a
// contact's frame but only mu N / sqrt(2) between them, and a turning robot's lateral force
// sweeps every direction: the slide-out speed lies between 2^(-1/4) and 1 times the Coulomb
// speed, depending on where the robot points when it slides
TEST(GripTest, TheDefaultRobotSlidesOutOfATurnWithinThePyramidalConesBounds) {
  const SlideOut s = MeasureSlideOut(0);
  EXPECT_GE(s.speed_m_s, std::pow(2.0, -0.25) * s.predicted_m_s);
  EXPECT_LE(s.speed_m_s, s.predicted_m_s);
}

TEST(GripTest, WithTheFanTheRobotSlidesOutOfATurnWithinThePyramidalConesBounds) {
  const SlideOut s = MeasureSlideOut(1.0);
  EXPECT_GE(s.speed_m_s, std::pow(2.0, -0.25) * s.predicted_m_s);
  EXPECT_LE(s.speed_m_s, s.predicted_m_s);
  EXPECT_GT(s.speed_m_s, MeasureSlideOut(0).speed_m_s * 1.2) << "the fan added no grip";
}

// with elliptic cones the grip is mu N in every direction: the Coulomb limit within 10 %
TEST(GripTest, WithEllipticConesTheSlideOutSpeedIsTheCoulombLimitWithinTenPercent) {
  for (double downforce_n : {0.0, 1.0}) {
    const SlideOut s = MeasureSlideOut(downforce_n, true);
    EXPECT_NEAR(s.speed_m_s, s.predicted_m_s, 0.10 * s.predicted_m_s) << downforce_n;
  }
}

TEST(GripTest, AtFullCommandFromStandstillTheWheelsSpinAndTractionSetsTheAcceleration) {
  auto kernel = MakeKernel(GyroRobotWith(""));
  for (int i = 0; i < 500; ++i) kernel->Step();
  const double mass_kg = mj_getTotalmass(&kernel->mj_model());
  const double traction_m_s2 = kMu * WheelLoad_n(*kernel, 0) / mass_kg;
  SetSignal(*kernel, "left.command", 1023);
  SetSignal(*kernel, "right.command", 1023);
  const double v0 = ChassisMotion(*kernel).forward_m_s;
  for (int i = 0; i < 50; ++i) kernel->Step();
  const double v = ChassisMotion(*kernel).forward_m_s;
  const double rim_m_s = kWheelRadius_m * 0.5 *
                         (JointSpeed(*kernel, "left_wheel") + JointSpeed(*kernel, "right_wheel"));
  const double slip = (rim_m_s - v) / rim_m_s;
  std::printf(
      "first 50 ms at full command: %.2f m/s^2 (Coulomb %.2f), rim %.3f m/s, chassis "
      "%.3f m/s, slip ratio %.2f\n",
      (v - v0) / 0.05, traction_m_s2, rim_m_s, v, slip);
  EXPECT_NEAR((v - v0) / 0.05, traction_m_s2, 0.10 * traction_m_s2);
  EXPECT_GT(slip, 0.5);
}

}  // namespace
}  // namespace unimouse
