// SPDX-License-Identifier: GPL-3.0-or-later
// The whole robot of tables 4.1-4.6, driven through its H-bridge inputs: it drives straight,
// spins in place, and its body motion matches the differential-drive kinematics of eq. 3.26 and
// 3.28 computed from its own wheel speeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "inline_assets.h"
#include "plugin_rig.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

using testing::JointSpeed;
using testing::MakeKernel;
using testing::SetSignal;

constexpr double kWheelRadius_m = 0.016;
constexpr double kHalfTrack_m = 0.048;  // d of eq. 3.24-3.27

class RobotTest : public ::testing::Test {
 protected:
  void SetUp() override { kernel_ = MakeKernel(testing::ReadBundledRobot()); }
  void Drive(double left, double right, int steps) {
    SetSignal(*kernel_, "left.command", left);
    SetSignal(*kernel_, "right.command", right);
    for (int i = 0; i < steps; ++i) kernel_->Step();
  }
  Pose2D Pose() const { return kernel_->world().RobotPose(kernel_->state().data()); }
  // forward speed and yaw rate of the chassis
  double Speed() const {
    const mjData& d = kernel_->state().data();
    const double yaw = Pose().yaw_rad;
    return d.qvel[0] * std::cos(yaw) + d.qvel[1] * std::sin(yaw);
  }
  double YawRate() const { return kernel_->state().data().qvel[5]; }

  std::unique_ptr<Kernel> kernel_;
};

double AngleDifference(double a, double b) { return std::remainder(a - b, 2 * std::numbers::pi); }

TEST_F(RobotTest, EqualCommandsDriveStraight) {
  const Pose2D start = Pose();
  SetSignal(*kernel_, "left.command", 700);
  SetSignal(*kernel_, "right.command", 700);
  while (std::hypot(Pose().x_m - start.x_m, Pose().y_m - start.y_m) < 1.0) {
    kernel_->Step();
    ASSERT_LT(kernel_->state().data().time, 5) << "did not cover 1 m";
  }
  EXPECT_LT(std::fabs(AngleDifference(Pose().yaw_rad, start.yaw_rad)), std::numbers::pi / 180);
  EXPECT_NEAR(Pose().y_m - start.y_m, 1.0, 0.01);  // it started facing north
}

TEST_F(RobotTest, OppositeCommandsSpinInPlace) {
  const Pose2D start = Pose();
  Drive(700, -700, 2000);
  // left forward, right backward: clockwise, so the yaw rate is negative
  EXPECT_LT(YawRate(), -1);
  EXPECT_LT(std::hypot(Pose().x_m - start.x_m, Pose().y_m - start.y_m), 0.01);
}

TEST_F(RobotTest, BodyMotionMatchesEquations326And328FromWheelSpeeds) {
  // a wide arc: in tight fast turns the wheels slide sideways, as real ones do
  Drive(600, 700, 1500);
  const double vl = kWheelRadius_m * JointSpeed(*kernel_, "left_wheel");
  const double vr = kWheelRadius_m * JointSpeed(*kernel_, "right_wheel");
  const double v = (vr + vl) / 2;                       // eq. 3.28
  const double omega = (vr - vl) / (2 * kHalfTrack_m);  // eq. 3.26
  EXPECT_NEAR(Speed(), v, 0.05 * std::fabs(v));
  EXPECT_NEAR(YawRate(), omega, 0.05 * std::fabs(omega));
  EXPECT_GT(omega, 0);  // the faster right wheel turns it counter-clockwise
}

TEST_F(RobotTest, TopSpeedIsCloseToTheMotorsNoLoadSpeed) {
  Drive(1023, 1023, 2000);
  // no-load: 6 V / 0.079025 N m/A x 0.016 m = 1.2148 m/s; rolling friction and the caster take
  // little (docs/performance.md records the measured figure)
  const double no_load = 6 / 0.079025 * kWheelRadius_m;
  EXPECT_LT(Speed(), no_load * 1.001);
  EXPECT_GT(Speed(), no_load * 0.97);
}

TEST_F(RobotTest, WithoutCommandsItStaysPut) {
  const Pose2D start = Pose();
  Drive(0, 0, 2000);
  EXPECT_LT(std::hypot(Pose().x_m - start.x_m, Pose().y_m - start.y_m), 1e-4);
}

// robots/unimouse-half.yaml in a half-size corridor: 90 mm cells, 84 mm between the 6 mm walls
TEST(HalfSizeRobotTest, DrivesAlongAHalfSizeCorridorWithoutTouchingItsWalls) {
  Maze maze(32, 32);
  for (int y = 0; y < 32; ++y) maze.SetWall({0, y}, Heading::kEast, true);
  auto kernel = MakeKernel(ReadTextFile(UNIMOUSE_SOURCE_DIR "/robots/unimouse-half.yaml"), &maze);
  ASSERT_EQ(kernel->world().maze_dimensions().cell_m, 0.09);
  SetSignal(*kernel, "left.command", 300);
  SetSignal(*kernel, "right.command", 300);
  for (int i = 0; i < 1500; ++i) {
    kernel->Step();
    ASSERT_FALSE(kernel->world().RobotTouchesScenery(kernel->state().data())) << "step " << i;
  }
  const Pose2D p = kernel->world().RobotPose(kernel->state().data());
  EXPECT_GT(p.y_m, 0.3);            // on its way north, several cells
  EXPECT_NEAR(p.x_m, 0.045, 0.01);  // still in the middle of the corridor
}

// without the armature its small wheels need (the robot file says why), the half-size robot's
// physics blows up on the first step; the message names the joint and its motor in the file
TEST(HalfSizeRobotTest, WithoutItsWheelsArmatureItDivergesNamingTheWheelAndMotorLines) {
  std::string yaml = ReadTextFile(UNIMOUSE_SOURCE_DIR "/robots/unimouse-half.yaml");
  const std::string armature = ", armature_kg_m2: 1.0e-6";
  for (size_t at = yaml.find(armature); at != std::string::npos; at = yaml.find(armature)) {
    yaml.erase(at, armature.size());
  }
  // where the file declares the left wheel's joint and its motor, line and column from 1
  const auto place = [&yaml](const std::string& text) {
    const size_t at = yaml.find(text);
    const size_t line_start = yaml.rfind('\n', at) + 1;
    return "robot.yaml:" + std::to_string(std::count(yaml.begin(), yaml.begin() + at, '\n') + 1) +
           ":" + std::to_string(at - line_start - 1);  // the '{' before the text
  };
  const std::string joint = place("name: left_wheel, type: hinge");
  const std::string motor = place("name: left_motor, joint: left_wheel");
  auto kernel = MakeKernel(yaml);
  SetSignal(*kernel, "left.command", 300);
  SetSignal(*kernel, "right.command", 300);
  try {
    for (int i = 0; i < 100; ++i) kernel->Step();
    FAIL() << "no divergence in 0.1 s";
  } catch (const RuntimeFault& e) {
    EXPECT_EQ(std::string(e.what()),
              "physics diverged at t=0.001 s: the acceleration of joint 'left_wheel' of body "
              "'left_wheel' (" +
                  joint + "), actuator 'left_motor' (" + motor +
                  ") became infinite or not a number; check masses, inertias, timestep and "
                  "controls");
  }
}

}  // namespace
}  // namespace unimouse
