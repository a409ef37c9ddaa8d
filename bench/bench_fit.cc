// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse fit`'s cost: the four motor parameters (each motor's Kt and Ra) fitted from a
// 60-second log of the sysid sequence (arduino-lib/examples/sysid, with the ramps run twice),
// made by the bundled robot with each constant 20 % off and the counts rounded as an encoder
// rounds them. docs/performance.md quotes the median.
#include <benchmark/benchmark.h>

#include <cmath>

#include "bundled_components.h"
#include "fit.h"
#include "replay.h"
#include "robot_spec.h"
#include "text_file.h"

namespace {

using namespace unimouse;

struct Segment {
  double duration_s;
  double left_from, left_to, right_from, right_to;
};

// the sysid sketch's sequence, its ramps run twice: 60.4 s
const Segment kSequence[] = {
    {1, 0, 0, 0, 0},   {8, 0, 700, 0, 700},
    {1.5, 0, 0, 0, 0}, {8, 0, -700, 0, -700},
    {1.5, 0, 0, 0, 0}, {4, 0, 400, 0, 400},
    {1, 0, 0, 0, 0},   {4, 0, -400, 0, -400},
    {3, 0, 0, 0, 0},   {1.2, 100, 100, 100, 100},
    {1.2, 0, 0, 0, 0}, {1.2, -100, -100, -100, -100},
    {1.2, 0, 0, 0, 0}, {1.2, 200, 200, 200, 200},
    {1.2, 0, 0, 0, 0}, {1.2, -200, -200, -200, -200},
    {1.2, 0, 0, 0, 0}, {1.2, 300, 300, 300, 300},
    {1.2, 0, 0, 0, 0}, {1.2, -300, -300, -300, -300},
    {1.2, 0, 0, 0, 0}, {1.5, -150, -150, 150, 150},
    {1.5, 0, 0, 0, 0}, {1.5, 150, 150, -150, -150},
    {1.5, 0, 0, 0, 0}, {1.5, -300, -300, 300, 300},
    {1.5, 0, 0, 0, 0}, {1.5, 300, 300, -300, -300},
    {1.5, 0, 0, 0, 0}, {2, 0, 0, 0, 0},
};

// the log a robot with these constants would write, rounded to whole counts
fit::SysidLog MakeLog(const RobotSpec& truth, const PluginRegistry& registry) {
  fit::SysidLog log;
  log.file = "bench.csv";
  double start = 0;
  for (const Segment& s : kSequence) {
    for (int k = 0; k < std::lround(s.duration_s * 100); ++k) {
      const double into = k / (s.duration_s * 100);
      log.time_s.push_back(start + k * 0.01);
      log.left_command.push_back(std::trunc(s.left_from + (s.left_to - s.left_from) * into));
      log.right_command.push_back(std::trunc(s.right_from + (s.right_to - s.right_from) * into));
      log.battery_v.push_back(6);
      log.line.push_back(static_cast<int>(log.line.size()) + 2);
    }
    start += s.duration_s;
  }
  log.left_counts.assign(log.rows(), 0);
  log.right_counts.assign(log.rows(), 0);
  const fit::Channels speeds = fit::ReplayChannels(truth, fit::WireRobot(truth), registry, log);
  double left = 0, right = 0;
  for (size_t i = 1; i < log.rows(); ++i) {
    const double dt = log.time_s[i] - log.time_s[i - 1];
    left += speeds.values[0][i - 1] * dt;
    right += speeds.values[1][i - 1] * dt;
    log.left_counts[i] = std::floor(left);
    log.right_counts[i] = std::floor(right);
  }
  return log;
}

void BM_FitFourMotorParametersFrom60sLog(benchmark::State& state) {
  PluginRegistry registry;
  AddBundledComponents(registry);
  const std::string file = UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml";
  const RobotSpec robot = ParseRobotSpec(ReadTextFile(file), file);
  RobotSpec truth = robot;
  fit::SetParameter(truth, {"left_motor", "kt_nm_per_a"}, 0.079025 * 1.2);
  fit::SetParameter(truth, {"left_motor", "resistance_ohm"}, 16.66667 * 0.8);
  fit::SetParameter(truth, {"right_motor", "kt_nm_per_a"}, 0.079025 * 0.8);
  fit::SetParameter(truth, {"right_motor", "resistance_ohm"}, 16.66667 * 1.2);
  const fit::SysidLog log = MakeLog(truth, registry);
  int replays = 0;
  for (auto _ : state) {
    const fit::FitReport report = fit::FitRobot(robot, registry, {log});
    replays = report.replays;
    benchmark::DoNotOptimize(report);
  }
  state.counters["replays"] = replays;
  state.counters["log_s"] = log.time_s.back();
}
BENCHMARK(BM_FitFourMotorParametersFrom60sLog)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1)
    ->Repetitions(3);

}  // namespace
