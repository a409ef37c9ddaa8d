// SPDX-License-Identifier: GPL-3.0-or-later
// Components that exist only for tests: they record what the kernel does to them, or drive the
// robot in a known way.
#ifndef UNIMOUSE_TESTS_PROBE_COMPONENTS_H_
#define UNIMOUSE_TESTS_PROBE_COMPONENTS_H_

#include <string>
#include <vector>

#include "unimouse/component.h"

namespace unimouse::testing {

/// Every hook call of every Probe, in order, as "sense:tag" etc.
std::vector<std::string>& ProbeEvents();

struct ProbeParams {
  std::string tag;
  double torque_nm = 0;
  int count = 1;
  std::string mode = "a";
  bool enabled = true;
  template <class V>
  void Visit(V& v) {
    v("tag", tag, "name written into the event log", param::Required{});
    v("torque_nm", torque_nm, "torque written to left_motor in Actuate", param::Range{-1, 1});
    v("count", count, "a whole number for validation tests", param::Range{1, 10});
    v("mode", mode, "a word for validation tests", param::OneOf{"a|b"});
    v("enabled", enabled, "a flag for validation tests");
  }
};

/// Records its hooks; in Sense also the chassis x position it sees; writes torque_nm.
class Probe final : public Component {
 public:
  static constexpr const char* kTypeName = "test.probe";
  static constexpr const char* kSummary = "records hook calls";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = ProbeParams;
  explicit Probe(Params p) : p_(std::move(p)) {}
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;
  void Actuate(const ActuateContext& ctx) const override;

 private:
  Params p_;
  int actuator_ = -1;
  int chassis_ = -1;
};

struct RandomTorqueParams {
  double scale_nm = 0.002;
  template <class V>
  void Visit(V& v) {
    v("scale_nm", scale_nm, "standard deviation of the torque on each wheel");
  }
};

/// Drives both wheels with fresh Gaussian torques from its own random stream every tick.
class RandomTorque final : public Component {
 public:
  static constexpr const char* kTypeName = "test.random_torque";
  static constexpr const char* kSummary = "random wheel torques";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = RandomTorqueParams;
  explicit RandomTorque(Params p) : p_(p) {}
  void Bind(BindContext& ctx) override;
  void Actuate(const ActuateContext& ctx) const override;

 private:
  Params p_;
  int left_ = -1, right_ = -1;
  RngId rng_;
};

struct SignalParams {
  std::string read;
  std::string write;
  template <class V>
  void Visit(V& v) {
    v("read", read, "signal to read, '' for none");
    v("write", write, "signal to write, '' for none");
  }
};

/// Declares one read and one write signal; copies read + 1 into write.
class SignalRelay final : public Component {
 public:
  static constexpr const char* kTypeName = "test.relay";
  static constexpr const char* kSummary = "signal relay";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = SignalParams;
  explicit SignalRelay(Params p) : p_(std::move(p)) {}
  void Bind(BindContext& ctx) override;
  void Actuate(const ActuateContext& ctx) const override;

 private:
  Params p_;
  SignalId in_, out_;
};

struct TalkerParams {
  std::string text = "hello";
  template <class V>
  void Visit(V& v) {
    v("text", text, "what it logs every step, followed by the step number");
  }
};

/// Logs one text line every step, as a firmware's log channel would.
class Talker final : public Component {
 public:
  static constexpr const char* kTypeName = "test.talker";
  static constexpr const char* kSummary = "logs a line every step";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = TalkerParams;
  explicit Talker(Params p) : p_(std::move(p)) {}
  void Bind(BindContext&) override {}
  void Actuate(const ActuateContext& ctx) const override {
    ctx.Log(p_.text + " " + std::to_string(ctx.step()));
  }

 private:
  Params p_;
};

struct MujocoErrorParams {
  int at_step = 5;
  std::string where = "hook";
  template <class V>
  void Visit(V& v) {
    v("at_step", at_step, "the step at which MuJoCo reports an error", param::NonNegative{});
    v("where", where, "hook: in this component's own MuJoCo call; physics: in mj_step2",
      param::OneOf{"hook|physics"});
  }
};

/// Makes MuJoCo report an error at a chosen step: asks its stack for more than it holds, or
/// leaves it so full that the physics step after the hooks runs out.
class MujocoError final : public Component {
 public:
  static constexpr const char* kTypeName = "test.mujoco_error";
  static constexpr const char* kSummary = "makes MuJoCo report an error";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = MujocoErrorParams;
  explicit MujocoError(Params p) : p_(std::move(p)) {}
  void Bind(BindContext&) override {}
  void Actuate(const ActuateContext& ctx) const override;

 private:
  Params p_;
};

struct GyroParams {
  std::string body = "chassis";
  std::string rate_out = "gyro.yaw_rate_rad_s";
  template <class V>
  void Visit(V& v) {
    v("body", body, "body whose yaw rate it measures");
    v("rate_out", rate_out, "signal it writes: yaw rate, rad/s, counter-clockwise positive");
  }
};

/// A sensor that is not a ToF: writes the body's yaw rate every step, as a gyro would.
class Gyro final : public Component {
 public:
  static constexpr const char* kTypeName = "test.gyro";
  static constexpr const char* kSummary = "yaw rate gyro";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = GyroParams;
  explicit Gyro(Params p) : p_(std::move(p)) {}
  void Bind(BindContext& ctx) override;
  void Sense(const SenseContext& ctx) const override;

 private:
  Params p_;
  int body_ = -1;
  SignalId rate_;
};

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_PROBE_COMPONENTS_H_
