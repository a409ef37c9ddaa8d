// SPDX-License-Identifier: GPL-3.0-or-later
#include "mms_physical.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

constexpr double kPi = std::numbers::pi;
// the four headings, counter-clockwise from east, as cell steps
constexpr int kDx[4] = {1, 0, -1, 0};
constexpr int kDy[4] = {0, 1, 0, -1};
constexpr const char* kHeadingNames[4] = {"east", "north", "west", "south"};

// robots/unimouse.yaml at the classic maze's scale: 16 mm wheels, 358.32 counts a wheel turn,
// 96 mm between the wheels
constexpr double kWheelRadius_m = 0.016;
constexpr double kCountsPerTurn = 358.32;
constexpr double kTrack_m = 0.096;
constexpr double kClassicCell_m = 0.18;
constexpr double kSensorAhead_m = 0.06;  // the front sensor ahead of the axle

// the 45-degree sensors at the front corners, beside the axle's middle
constexpr double kSensorSide_m = 0.048;

// H-bridge commands: cruising, the last and first centimetres, turning at most; steering at most
constexpr double kForward = 300;
constexpr double kSlow = 150;
constexpr double kTurn = 130;
constexpr double kMaxCorrection = 120;
constexpr double kSettle_s = 0.08;
// how far the robot rolls on at kSlow once the wheels stop: a move ends this short of the centre
constexpr double kCoast_m = 0.01;

// a quarter turn is closed on the encoders' heading: the command is proportional to what is left
// (kTurn from half a radian), less a damping on the turning rate that brakes the robot before
// the heading instead of letting it roll past (stopping the wheels at 45 let it roll 2.5
// degrees on); the rate is smoothed over 20 ms, as one encoder count a millisecond is 3 rad/s.
// A command that pushes on to the heading is at least kTurnMin, so that the turn does not stall
// short of it against the friction of the tyres and the caster. The turn ends once the estimate
// has been within half a degree for 20 ms, at rest
constexpr double kTurnGain_per_rad = 260;
constexpr double kTurnDamp_per_radps = 40;
constexpr double kTurnMin = 45;
constexpr double kTurnRate_s = 0.02;
constexpr double kTurnDone_rad = 0.004;      // pushes on while farther than this
constexpr double kTurnResidual_rad = 0.009;  // half a degree
constexpr double kTurnStill_radps = 0.1;
constexpr int kTurnStillTicks = 20;

// steering on the estimated offset from the corridor's middle and heading: at cruise a command
// difference c turns the robot by about c / 14 radians a metre (c / 300 of the speed on each
// wheel, over half the track), so these gains bring an offset back within about 10 cm, damped
constexpr double kSteerOffset_per_m = 2200;
constexpr double kSteerHeading_per_rad = 500;

// the side walls correct the estimate: each reading says where the wall is at the point the ray
// hits it, about 0.1 m ahead of the axle; a wrong offset shows at once, a wrong heading as it
// grows with the distance driven. An observer in distance with these gains (natural distance
// 5 cm, damping 0.7) learns both within a cell; at about 12 mm a reading, one millimetre of
// error turns the estimate by a quarter of a degree, so the sensors' noise (2.8 % of about
// 5 cm) stays well under a degree
constexpr double kObserveAhead_m = 0.096;       // the hit point ahead of the axle, centred
constexpr double kObserveLookahead_per_m = 28;  // 2 x 0.7 x 20
constexpr double kObserveHeading_per_m2 = 400;  // 20^2
constexpr double kObserveStep_m = 0.015;        // the most distance one reading stands for
constexpr double kObserveGate_m = 0.015;        // a reading this far off is an edge or a post
// in the last 4 cm before a wall ahead the 45-degree rays hit that wall (at the centre they read
// 34 mm, as a side wall 1.2 cm nearer would), so the side walls are not observed there
constexpr double kObserveEnd_m = 0.04;

// a - b in (-pi, pi]
double AngleDiff(double a, double b) { return std::remainder(a - b, 2 * kPi); }

std::string Metres(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", v);
  return text;
}

}  // namespace

MmsRobot::MmsRobot(Session& session, const MmsControl& control)
    : session_(session), control_(control) {
  const Kernel& kernel = session_.kernel();
  auto signal = [&](const char* name) {
    const int id = kernel.model().FindSignal(name);
    UNIMOUSE_THROW_UNLESS(id >= 0, "mms --physical drives robots/unimouse.yaml's signals: robot '" +
                                       session_.robot().name + "' has no signal '" + name + "'");
    return id;
  };
  left_command_ = signal("left.command");
  right_command_ = signal("right.command");
  left_counts_ = signal("left.encoder_counts");
  right_counts_ = signal("right.encoder_counts");
  tof_left_ = signal("tof.left_m");
  tof_front_ = signal("tof.front_m");
  tof_right_ = signal("tof.right_m");
  cell_m_ = kernel.world().maze_dimensions().cell_m;
  // a half-size robot is the classic one at half scale
  scale_ = cell_m_ / kClassicCell_m;
  metres_per_count_ = 2 * kPi * kWheelRadius_m * scale_ / kCountsPerTurn;
  track_m_ = kTrack_m * scale_;
  const Pose2D spawn = kernel.world().spawn();
  UNIMOUSE_THROW_UNLESS(
      spawn.x_m < cell_m_ && spawn.y_m < cell_m_ &&
          std::abs(AngleDiff(spawn.yaw_rad, kPi / 2)) < 0.1,
      "mms --physical: the mms mouse starts in cell (0, 0) facing north, and this maze's start "
      "is elsewhere");
  Reset();
}

void MmsRobot::Reset() {
  Kernel& kernel = session_.kernel();
  const Pose2D spawn = kernel.world().spawn();
  kernel.world().PlaceRobot(kernel.state().data(), spawn);
  kernel.state().signals()[left_command_] = 0;
  kernel.state().signals()[right_command_] = 0;
  x_ = y_ = 0;
  heading_ = 1;
  est_x_m_ = spawn.x_m;
  est_y_m_ = spawn.y_m;
  est_yaw_rad_ = kPi / 2;
  seen_ = {};
}

double MmsRobot::now_s() { return session_.kernel().state().data().time; }

bool MmsRobot::Tick(double left, double right) {
  Kernel& kernel = session_.kernel();
  std::vector<double>& signals = kernel.state().signals();
  signals[left_command_] = std::clamp(std::round(left), -1023.0, 1023.0);
  signals[right_command_] = std::clamp(std::round(right), -1023.0, 1023.0);
  session_.Step();
  if (session_.Over()) return false;

  // dead reckoning: the wheels' travel this tick, along the mean heading
  const double left_m = signals[left_counts_] * metres_per_count_;
  const double right_m = signals[right_counts_] * metres_per_count_;
  const double travel_m = (left_m + right_m) / 2;
  const double turn_rad = (right_m - left_m) / track_m_;
  est_x_m_ += travel_m * std::cos(est_yaw_rad_ + turn_rad / 2);
  est_y_m_ += travel_m * std::sin(est_yaw_rad_ + turn_rad / 2);
  est_yaw_rad_ += turn_rad;

  // a contact is counted when it begins, as the micromouse scenario counts them
  const int64_t contacts = kernel.contacts().wall_contacts(0);
  if (contacts > wall_contacts_) {
    wall_contacts_ = contacts;
    move_contact_ = true;
  }
  return true;
}

bool MmsRobot::Settle() {
  const double until_s = now_s() + kSettle_s;
  while (now_s() < until_s) {
    if (!Tick(0, 0)) return false;
  }
  return true;
}

MmsMotion MmsRobot::Drive(long cells) {
  const double start_s = now_s();
  move_contact_ = false;
  const int dx = kDx[heading_];
  const int dy = kDy[heading_];
  const double target_x_m = (double(x_ + dx * cells) + 0.5) * cell_m_;
  const double target_y_m = (double(y_ + dy * cells) + 0.5) * cell_m_;
  auto to_go_m = [&] { return (target_x_m - est_x_m_) * dx + (target_y_m - est_y_m_) * dy; };
  const double start_to_go_m = to_go_m();
  const double budget_s = control_.move_budget_s + double(cells) * control_.cell_budget_s;
  const double s = scale_;
  const std::vector<double>& signals = session_.kernel().state().signals();
  // the face of the wall that may close the last cell, from the front sensor
  const double wall_face_m = cell_m_ / 2 -
                             session_.kernel().world().maze_dimensions().wall_thickness_m / 2 -
                             kSensorAhead_m * s;
  double min_left_m = 9, min_right_m = 9, min_front_m = 9;
  double last_front_m = signals[tof_front_];
  double last_left_m = signals[tof_left_], last_right_m = signals[tof_right_];
  // the corridor: its left, and the middle's place across it; half its width between the faces
  const double nx = -dy, ny = dx;
  const double middle_m = (x_ + 0.5) * cell_m_ * nx + (y_ + 0.5) * cell_m_ * ny;
  const double half_width_m =
      cell_m_ / 2 - session_.kernel().world().maze_dimensions().wall_thickness_m / 2;
  const double side_m = control_.side_wall_m * s;
  double observed_at_m = 0;  // the distance driven at the side walls' last correction
  for (;;) {
    const double left_m = signals[tof_left_];
    const double front_m = signals[tof_front_];
    const double right_m = signals[tof_right_];
    // a fresh reading of the wall ahead of the last cell tells how far its centre is: the
    // encoders' estimate along the heading is put right by it
    if (front_m != last_front_m && front_m < control_.front_wall_m * s &&
        std::abs(front_m - wall_face_m - to_go_m()) < 0.05 * s) {
      const double shift_m = to_go_m() - (front_m - wall_face_m);
      est_x_m_ += shift_m * dx;
      est_y_m_ += shift_m * dy;
    }
    last_front_m = front_m;

    // the offset from the corridor's middle (positive to the left) and the heading's error, as
    // estimated; a fresh side reading says where the offset is, given the heading
    double offset_m = est_x_m_ * nx + est_y_m_ * ny - middle_m;
    double heading_rad = AngleDiff(est_yaw_rad_, heading_ * kPi / 2);
    const double c = std::cos(heading_rad), sn = std::sin(heading_rad);
    double error_m = 0;
    int errors = 0;
    const bool sides_seen = to_go_m() > kObserveEnd_m * s;
    if (sides_seen && left_m != last_left_m && left_m < side_m) {
      const double e = half_width_m - left_m * std::sin(kPi / 4 + heading_rad) -
                       (kSensorSide_m * c + kSensorAhead_m * sn) * s - offset_m;
      if (std::abs(e) < kObserveGate_m * s) error_m += e, ++errors;
    }
    if (sides_seen && right_m != last_right_m && right_m < side_m) {
      const double e = right_m * std::sin(kPi / 4 - heading_rad) +
                       (kSensorSide_m * c - kSensorAhead_m * sn) * s - half_width_m - offset_m;
      if (std::abs(e) < kObserveGate_m * s) error_m += e, ++errors;
    }
    last_left_m = left_m;
    last_right_m = right_m;
    const double travelled_m = start_to_go_m - to_go_m();
    if (errors > 0) {
      error_m /= errors;
      const double step_m = std::clamp(travelled_m - observed_at_m, 0.0, kObserveStep_m * s);
      observed_at_m = travelled_m;
      // the point ahead takes the first gain, the heading the second; the offset is what is
      // left of the point's correction
      const double heading_gain = kObserveHeading_per_m2 / (s * s) * step_m;
      const double ahead_gain = kObserveLookahead_per_m / s * step_m;
      const double turn_rad = heading_gain * error_m;
      const double shift_m = ahead_gain * error_m - kObserveAhead_m * s * turn_rad;
      est_x_m_ += shift_m * nx;
      est_y_m_ += shift_m * ny;
      est_yaw_rad_ += turn_rad;
      offset_m += shift_m;
      heading_rad += turn_rad;
    }

    const double go_m = to_go_m();
    // the last cell's side walls pass the 45-degree sensors about half a cell before its
    // centre; its wall ahead is seen before the front sensor gets too near to see it
    if (go_m < 0.11 * s && go_m > 0.07 * s) {
      min_left_m = std::min(min_left_m, left_m);
      min_right_m = std::min(min_right_m, right_m);
    }
    if (go_m < 0.09 * s && go_m > 0.04 * s) min_front_m = std::min(min_front_m, front_m);
    // a wall ahead nearer than the last cell's own stops the move; that one is 24 mm from the
    // front sensor at the centre, and the estimate, which its readings corrected, stops there
    if (go_m <= kCoast_m * s) break;
    if (front_m <= control_.front_stop_m * s && front_m - wall_face_m < go_m - kCoast_m * s) break;
    if (now_s() - start_s > budget_s) {
      session_.kernel().state().signals()[left_command_] = 0;
      session_.kernel().state().signals()[right_command_] = 0;
      const Pose2D p = session_.kernel().world().RobotPose(session_.kernel().state().data());
      return {now_s() - start_s, move_contact_, "stuck",
              "a move of " + std::to_string(cells) + " cell(s) " + kHeadingNames[heading_] +
                  " from (" + std::to_string(x_) + ", " + std::to_string(y_) +
                  ") did not finish in " + Metres(budget_s) +
                  " s of simulated time; the robot is at (" + Metres(p.x_m) + ", " + Metres(p.y_m) +
                  ") m"};
    }

    // positive steers left: back to the corridor's middle, along it
    const double correction =
        std::clamp(-kSteerOffset_per_m / s * offset_m - kSteerHeading_per_rad * heading_rad,
                   -kMaxCorrection, kMaxCorrection);
    // ramps over the first 3 cm and from 6 to 3 cm before the end, so that the wheels do not
    // slip and fool the encoders (a step down to kSlow left the estimate millimetres behind)
    double base = kForward;
    if (go_m < 0.06 * s) {
      base = kSlow + (kForward - kSlow) * std::max(0.0, go_m - 0.03 * s) / (0.03 * s);
    }
    if (travelled_m < 0.03 * s) {
      base = kSlow + (kForward - kSlow) * std::max(0.0, travelled_m) / (0.03 * s);
    }
    if (!Tick(base - correction, base + correction)) return Ended(start_s);
  }
  x_ += dx * int(cells);
  y_ += dy * int(cells);
  seen_ = {};
  seen_[heading_] = min_front_m < control_.front_wall_m * s;
  seen_[(heading_ + 1) % 4] = min_left_m < control_.side_wall_m * s;
  seen_[(heading_ + 3) % 4] = min_right_m < control_.side_wall_m * s;
  seen_[(heading_ + 2) % 4] = false;  // it came in that way
  if (!Settle()) return Ended(start_s);
  return Arrived(start_s);
}

MmsMotion MmsRobot::Turn(int quarter_turns) {
  const double start_s = now_s();
  move_contact_ = false;
  const int to = ((heading_ + quarter_turns) % 4 + 4) % 4;
  // closed on the encoders' heading (the constants above say how), until it rests on it
  double rate_radps = 0;
  int still = 0;
  for (;;) {
    const double left_rad = AngleDiff(to * kPi / 2, est_yaw_rad_);
    if (std::abs(left_rad) < kTurnResidual_rad && std::abs(rate_radps) < kTurnStill_radps) {
      if (++still >= kTurnStillTicks) break;
    } else {
      still = 0;
    }
    if (now_s() - start_s > control_.move_budget_s) {
      session_.kernel().state().signals()[left_command_] = 0;
      session_.kernel().state().signals()[right_command_] = 0;
      return {now_s() - start_s, move_contact_, "stuck",
              "a turn in cell (" + std::to_string(x_) + ", " + std::to_string(y_) +
                  ") did not finish in " + Metres(control_.move_budget_s) + " s of simulated time"};
    }
    double c =
        std::clamp(kTurnGain_per_rad * left_rad - kTurnDamp_per_radps * rate_radps, -kTurn, kTurn);
    if (std::abs(left_rad) > kTurnDone_rad && c * left_rad > 0 && std::abs(c) < kTurnMin) {
      c = left_rad > 0 ? kTurnMin : -kTurnMin;
    }
    const double before_rad = est_yaw_rad_;
    const double before_s = now_s();
    if (!Tick(-c, c)) return Ended(start_s);
    const double dt = now_s() - before_s;
    rate_radps += ((est_yaw_rad_ - before_rad) / dt - rate_radps) * std::min(1.0, dt / kTurnRate_s);
  }
  heading_ = to;
  if (!Settle()) return Ended(start_s);
  return Arrived(start_s);
}

MmsMotion MmsRobot::Ended(double start_s) {
  // a signal or the viewer's window ended the run, not the robot
  if (const std::string why = session_.interruption(); !why.empty()) {
    return {now_s() - start_s, move_contact_, "interrupted", why};
  }
  const std::string verdict = session_.verdict();
  return {
      now_s() - start_s, move_contact_, "error",
      verdict.empty() ? "the simulation ran out of time at " + Metres(now_s()) + " s" : verdict};
}

MmsMotion MmsRobot::Arrived(double start_s) {
  // the true pose: the mouse's cell and heading are where the robot really is, or the run ends
  const Pose2D p = session_.kernel().world().RobotPose(session_.kernel().state().data());
  const double offset_m = std::hypot(p.x_m - (x_ + 0.5) * cell_m_, p.y_m - (y_ + 0.5) * cell_m_);
  const double yaw_error_rad = std::abs(AngleDiff(heading_ * kPi / 2, p.yaw_rad));
  worst_offset_m_ = std::max(worst_offset_m_, offset_m);
  worst_yaw_error_rad_ = std::max(worst_yaw_error_rad_, yaw_error_rad);
  MmsMotion motion{now_s() - start_s, move_contact_, "", ""};
  const bool in_cell =
      int(std::floor(p.x_m / cell_m_)) == x_ && int(std::floor(p.y_m / cell_m_)) == y_;
  if (!in_cell || yaw_error_rad > control_.off_course_rad) {
    motion.failure = "off_course";
    motion.why = "the robot came to rest at (" + Metres(p.x_m) + ", " + Metres(p.y_m) +
                 ") m facing " + std::to_string(int(std::lround(p.yaw_rad * 180 / kPi))) +
                 " degrees, not in cell (" + std::to_string(x_) + ", " + std::to_string(y_) +
                 ") facing " + kHeadingNames[heading_];
  }
  return motion;
}

std::optional<bool> MmsRobot::SensedWall(int side) { return seen_[(heading_ + side) % 4]; }

nlohmann::json MmsRobot::Facts() const {
  return {{"wall_contacts", wall_contacts_},
          {"worst_offset_m", worst_offset_m_},
          {"worst_yaw_error_deg", worst_yaw_error_rad_ * 180 / kPi}};
}

}  // namespace unimouse
