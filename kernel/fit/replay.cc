// SPDX-License-Identifier: GPL-3.0-or-later
#include "replay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "kernel.h"
#include "unimouse/errors.h"

namespace unimouse::fit {
namespace {

// the imu reading that goes with a row is that of the step after the row's own: in lock-step the
// firmware's answer acts within the step whose frames it read, while the replay's commands act
// from the next step on (which the encoders' angles, read a step later here, make up for); the
// imu's Sense sees the motion at the start of its step, so its reading one step on is the
// firmware's at the row (measured: a step earlier or later leaves residuals of 0.05 rad/s at each
// spin's start and end, twenty times the chip's noise)
constexpr int kGyroLag_steps = 1;

// The count an encoder reports, expected over where within a count the wheel started: the
// wheel's angle in counts, less what algorithm 1 (the encoder component) holds back. That
// counts a whole count of travel since its last count, either way, so its remainder stays
// within one count of zero and turning back costs up to a count before the first is reported
// (a play of one count, as in a gear's backlash). Started anywhere within a count, the
// remainder is spread evenly over a count's width, which moves with the wheel and wraps: its
// mean moves with the wheel and stops at +-0.5 count. Without it a replay's wheel turned back
// a row or so early at each reversal, which a fit took for a longer time constant (the
// half-size robot's Ra 6-16 % high)
class ExpectedCount {
 public:
  explicit ExpectedCount(double counts) : zero_(counts), counts_(counts) {}
  void Move(double counts) {
    held_ = std::clamp(held_ + counts - counts_, -0.5, 0.5);
    counts_ = counts;
  }
  double reported() const { return counts_ - zero_ - held_; }

 private:
  double zero_, counts_;
  double held_ = 0;  // algorithm 1 starts with nothing held
};

// the component types a replay leaves out: they write files, wait for firmware, or measure
// what a log does not have
bool LeftOutOfReplay(const std::string& type) {
  return type == "unimouse.logger" || type == "unimouse.link" || type == "unimouse.tof_sensor";
}

const YamlNode* Param(const ComponentSpec& c, std::string_view key) {
  if (!c.params.IsMap()) return nullptr;
  for (const YamlEntry& e : c.params.entries) {
    if (e.first.scalar == key) return &e.second;
  }
  return nullptr;
}

std::string StringParam(const ComponentSpec& c, std::string_view key, std::string fallback) {
  const YamlNode* n = Param(c, key);
  return n != nullptr ? n->scalar : fallback;
}

double NumberParam(const ComponentSpec& c, std::string_view key, double fallback) {
  const YamlNode* n = Param(c, key);
  return n != nullptr ? n->AsNumber(key) : fallback;
}

const ComponentSpec* FindComponent(const RobotSpec& robot, const std::string& name) {
  for (const ComponentSpec& c : robot.components) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

void SetString(RobotSpec& robot, const std::string& component, const std::string& key,
               const std::string& value) {
  SetParameter(robot, {component, key}, 0);
  for (ComponentSpec& c : robot.components) {
    for (YamlEntry& e : c.params.entries) {
      if (c.name == component && e.first.scalar == key) e.second.scalar = value;
    }
  }
}

// the robot's actuator names and the joints they drive
std::string JointOfActuator(const RobotSpec& robot, const std::string& actuator) {
  for (const ActuatorSpec& a : robot.actuators) {
    if (a.name == actuator) return a.joint;
  }
  return "";
}

RobotWiring::Side WireSide(const RobotSpec& robot, const std::string& side) {
  RobotWiring::Side s;
  s.command_input = side + ".command";
  bool has_input = false;
  for (const std::string& input : robot.inputs) has_input = has_input || input == s.command_input;
  if (!has_input) {
    throw InputError(robot.file + ": the robot has no input '" + s.command_input +
                     "' for the log's " + side + "_command");
  }
  for (const ComponentSpec& c : robot.components) {
    if (c.type != "unimouse.encoder") continue;
    if (StringParam(c, "counts_out", "") != side + ".encoder_counts") continue;
    s.joint = StringParam(c, "joint", "");
    // encoder defaults: plugins/encoder (table 4.5)
    const double gear = NumberParam(c, "gear_ratio", 29.86);
    const double cpr = NumberParam(c, "cpr", 12);
    const YamlNode* x4 = Param(c, "quadrature_x4");
    const double edges = x4 != nullptr && x4->AsBool("quadrature_x4") ? 4 : 1;
    s.counts_per_rad = gear * cpr * edges / (2 * std::numbers::pi);
  }
  if (s.joint.empty()) {
    throw InputError(robot.file + ": no unimouse.encoder writes '" + side +
                     ".encoder_counts' for the log's " + side + "_counts");
  }
  for (const ComponentSpec& c : robot.components) {
    if (c.type == "unimouse.dc_motor" &&
        JointOfActuator(robot, StringParam(c, "actuator", "")) == s.joint) {
      s.motor = c.name;
    }
  }
  if (s.motor.empty()) {
    throw InputError(robot.file + ": no unimouse.dc_motor drives the " + side + " wheel ('" +
                     s.joint + "')");
  }
  return s;
}

}  // namespace

RobotWiring WireRobot(const RobotSpec& robot) {
  RobotWiring w;
  w.left = WireSide(robot, "left");
  w.right = WireSide(robot, "right");
  for (const ComponentSpec& c : robot.components) {
    if (c.type == "unimouse.battery") w.battery_emf_v = NumberParam(c, "emf_v", 6);
    if (c.type == "unimouse.imu" && w.imu.empty()) {
      w.imu = c.name;
      // plugins/imu: its signals' prefix is `out`, the component's name when empty
      const std::string out = StringParam(c, "out", "");
      w.imu_gyro_z = (out.empty() ? c.name : out) + ".gyro_z_rad_s";
    }
  }
  return w;
}

bool ParameterDrawn(const RobotSpec& robot, const ParameterRef& parameter) {
  const ComponentSpec* c = FindComponent(robot, parameter.component);
  return c != nullptr && c->type == "unimouse.imu" && Param(*c, parameter.key) == nullptr &&
         (parameter.key == "gyro_z_bias_dps" || parameter.key == "gyro_z_scale_error");
}

double ParameterValue(const RobotSpec& robot, const ParameterRef& parameter) {
  const ComponentSpec* c = FindComponent(robot, parameter.component);
  if (c == nullptr) {
    throw InputError(robot.file + ": no component '" + parameter.component + "'");
  }
  if (const YamlNode* n = Param(*c, parameter.key)) return n->AsNumber(parameter.key);
  // an imu without them draws its z gyro's bias and scale error; 0 is their centre
  if (c->type == "unimouse.imu" &&
      (parameter.key == "gyro_z_bias_dps" || parameter.key == "gyro_z_scale_error")) {
    return 0;
  }
  // a dc_motor's named model supplies what the file leaves out (plugins/dc_motor, table 3.1);
  // the replay asks the kernel-independent defaults through the same names
  const std::string model = StringParam(*c, "model", "pololu_30_1_lp");
  struct Known {
    const char* model;
    double kt, r;
  };
  static constexpr Known kModels[] = {
      {"pololu_30_1_lp", 0.079025, 16.66667},     {"pololu_50_1_lp", 0.1110591, 16.66667},
      {"pololu_100_1_lp", 0.18678114, 16.666666}, {"pololu_150_1_lp", 0.27014366, 16.216217},
      {"pololu_1000_1_lp", 1.5144416, 18.181818}, {"pololu_30_1_hp", 0.03494813, 3.75},
  };
  for (const Known& k : kModels) {
    if (model != k.model) continue;
    if (parameter.key == "kt_nm_per_a") return k.kt;
    if (parameter.key == "resistance_ohm") return k.r;
  }
  throw InputError(c->location.ToString() + ": component '" + parameter.component + "' gives no " +
                   parameter.key);
}

void SetParameter(RobotSpec& robot, const ParameterRef& parameter, double value) {
  for (ComponentSpec& c : robot.components) {
    if (c.name != parameter.component) continue;
    char text[40];
    std::snprintf(text, sizeof(text), "%.17g", value);
    for (YamlEntry& e : c.params.entries) {
      if (e.first.scalar == parameter.key) {
        e.second.scalar = text;
        return;
      }
    }
    YamlNode key, node;
    key.kind = node.kind = YamlNode::Kind::kScalar;
    key.scalar = parameter.key;
    node.scalar = text;
    key.location = node.location = c.params.location;
    c.params.entries.emplace_back(std::move(key), std::move(node));
    return;
  }
  throw InputError(robot.file + ": no component '" + parameter.component + "'");
}

Channels MeasuredChannels(const SysidLog& log) {
  Channels ch;
  ch.names = {"left_counts_per_s", "right_counts_per_s"};
  ch.values.resize(2);
  for (size_t i = 1; i < log.rows(); ++i) {
    const double dt = log.time_s[i] - log.time_s[i - 1];
    ch.values[0].push_back((log.left_counts[i] - log.left_counts[i - 1]) / dt);
    ch.values[1].push_back((log.right_counts[i] - log.right_counts[i - 1]) / dt);
  }
  if (!log.gyro_z_rad_s.empty()) {
    ch.gyro_z_rad_s.assign(log.gyro_z_rad_s.begin() + 1, log.gyro_z_rad_s.end());
  }
  return ch;
}

Channels ReplayChannels(const RobotSpec& robot, const RobotWiring& wiring,
                        const PluginRegistry& registry, const SysidLog& log) {
  RobotSpec replayed = robot;
  std::erase_if(replayed.components,
                [](const ComponentSpec& c) { return LeftOutOfReplay(c.type); });
  // the imu's own truth output is the yaw rate as the chip sees it (its Sense, not the step's
  // end); read through the chip's low-pass filter below, it is what the gyro reads, less errors
  const bool gyro = !log.gyro_z_rad_s.empty() && !wiring.imu.empty();
  std::string truth_out = "fit.imu_truth";
  double dlpf_alpha = 1;
  if (gyro) {
    const ComponentSpec* imu = FindComponent(replayed, wiring.imu);
    truth_out = StringParam(*imu, "truth_out", "");
    if (truth_out.empty()) {
      truth_out = "fit.imu_truth";
      SetString(replayed, wiring.imu, "truth_out", truth_out);
    }
    // plugins/imu: the part's default bandwidth (the LSM6DS3's 400 Hz, the others' 250 Hz)
    const double dlpf_hz = NumberParam(
        *imu, "dlpf_hz", StringParam(*imu, "part", "icm20602") == "lsm6ds3" ? 400 : 250);
    dlpf_alpha = 1 - std::exp(-2 * std::numbers::pi * dlpf_hz * robot.timestep_s);
  }
  KernelOptions options;
  options.seed = 1;
  options.log_sink = [](double, int, const std::string&, const std::string&) {};
  std::unique_ptr<Kernel> kernel = Kernel::Create(replayed, nullptr, registry, options);
  const Model& model = kernel->model();
  const mjModel& m = kernel->mj_model();
  const int left_in = model.FindSignal(wiring.left.command_input);
  const int right_in = model.FindSignal(wiring.right.command_input);
  const int left_q = m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, wiring.left.joint.c_str())];
  const int right_q = m.jnt_qposadr[mj_name2id(&m, mjOBJ_JOINT, wiring.right.joint.c_str())];
  const double dt = kernel->timestep_s();
  // the imu's reading and the true yaw rate it saw, when the log has a gyro to compare them with
  const int gyro_signal = gyro ? model.FindSignal(wiring.imu_gyro_z) : -1;
  const int truth_signal = gyro ? model.FindSignal(truth_out + ".gyro_z_rad_s") : -1;
  UNIMOUSE_DEMAND(!gyro || (gyro_signal >= 0 && truth_signal >= 0));
  // per step: the imu's reading and the filtered true rate, from step 0 on
  std::vector<double> step_gyro, step_rate;
  double filtered_rate = 0;
  const auto sample_gyro = [&] {
    if (!gyro) return;
    const std::vector<double>& signals = kernel->state().signals();
    filtered_rate += dlpf_alpha * (signals[truth_signal] - filtered_rate);
    step_gyro.push_back(signals[gyro_signal]);
    step_rate.push_back(filtered_rate);
  };
  sample_gyro();

  // a row's counts are the wheels' angles after as many steps as its time; its commands then
  // hold until the next row's time (the sysid sketch reads, then commands, then logs: replaying
  // the simulator's own log this way matches it to the encoders' quantisation)
  const double t0 = log.time_s.front();
  const mjData& d = kernel->state().data();
  ExpectedCount left(d.qpos[left_q] * wiring.left.counts_per_rad);
  ExpectedCount right(d.qpos[right_q] * wiring.right.counts_per_rad);
  std::vector<double> left_counts, right_counts;
  std::vector<int64_t> row_steps;
  int64_t step = 0;
  for (size_t i = 0; i < log.rows(); ++i) {
    const int64_t row_step = std::llround((log.time_s[i] - t0) / dt);
    while (step < row_step) {
      kernel->Step();
      sample_gyro();
      left.Move(d.qpos[left_q] * wiring.left.counts_per_rad);
      right.Move(d.qpos[right_q] * wiring.right.counts_per_rad);
      ++step;
    }
    left_counts.push_back(left.reported());
    right_counts.push_back(right.reported());
    row_steps.push_back(row_step);
    // the row's commands, as the voltage the log's battery gives through the file's bridges
    const double scale = wiring.battery_emf_v > 0 ? log.battery_v[i] / wiring.battery_emf_v : 1;
    kernel->state().signals()[left_in] = log.left_command[i] * scale;
    kernel->state().signals()[right_in] = log.right_command[i] * scale;
  }
  for (int extra = 0; gyro && extra < kGyroLag_steps; ++extra) {
    kernel->Step();
    sample_gyro();
  }
  kernel->Finish();

  Channels ch;
  ch.names = {"left_counts_per_s", "right_counts_per_s"};
  ch.values.resize(2);
  for (size_t i = 1; i < log.rows(); ++i) {
    const double span = log.time_s[i] - log.time_s[i - 1];
    ch.values[0].push_back((left_counts[i] - left_counts[i - 1]) / span);
    ch.values[1].push_back((right_counts[i] - right_counts[i - 1]) / span);
  }
  for (size_t i = 1; gyro && i < log.rows(); ++i) {
    const size_t at = static_cast<size_t>(row_steps[i] + kGyroLag_steps);
    ch.gyro_z_rad_s.push_back(step_gyro[at]);
    ch.yaw_rate_rad_s.push_back(step_rate[at]);
  }
  return ch;
}

}  // namespace unimouse::fit
