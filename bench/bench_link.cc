// SPDX-License-Identifier: GPL-3.0-or-later
// The link: how evenly real-time pacing releases 1 kHz steps over 60 s with the full robot
// simulated, and what a lock-step firmware adds to a step: the micromouse example in the
// simulator's process (inproc:) and as a process of its own (native:), beside the same robot
// driven by direct commands, in one run; the racer beside its own commands replayed.
#include <benchmark/benchmark.h>

#include <chrono>
#include <utility>
#include <vector>

#include "bundled_components.h"
#include "kernel.h"
#include "maze.h"
#include "real_time_pacer.h"
#include "world.h"

namespace {

using namespace unimouse;

PluginRegistry Registry() {
  PluginRegistry r;
  AddBundledComponents(r);
  return r;
}

RobotSpec Robot(const std::string& link) {
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  std::erase_if(robot.components,
                [](const ComponentSpec& c) { return c.type == "unimouse.logger"; });
  if (!link.empty()) {
    robot.components.push_back({"unimouse.link",
                                "link",
                                std::nullopt,
                                ParseYaml("{transport: '" + link + "', beliefs_out: ''}", "bench"),
                                {"bench", 1, 1}});
  }
  return robot;
}

// the benchmark wrote the robot file itself: its link may start the firmware
std::unique_ptr<Kernel> WithLink(const std::string& link, const PluginRegistry& registry,
                                 const Maze* maze = nullptr) {
  KernelOptions options;
  options.trust_robot_file = true;
  return Kernel::Create(Robot(link), maze, registry, options);
}

// the main job's maze
const Maze* Japan2018() {
  static const Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  return &maze;
}

void BM_RealTimePacing60s(benchmark::State& bench) {
  const PluginRegistry registry = Registry();
  auto kernel = Kernel::Create(Robot(""), nullptr, registry, 1);
  kernel->state().signals()[kernel->model().FindSignal("left.command")] = 600;
  kernel->state().signals()[kernel->model().FindSignal("right.command")] = 600;
  PacingReport report;
  for (auto _ : bench) {
    RealTimePacer pacer(kernel->timestep_s());
    for (int i = 0; i < 60000; ++i) {
      kernel->Step();
      pacer.Wait(kernel->state().step());
    }
    report = pacer.Report();
  }
  bench.counters["p50_us"] = report.lateness_p50_us;
  bench.counters["p99_us"] = report.lateness_p99_us;
  bench.counters["max_us"] = report.lateness_max_us;
  bench.counters["late_steps"] = static_cast<double>(report.late_steps);
}
BENCHMARK(BM_RealTimePacing60s)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// per step: the full robot driven by a firmware process in lock-step, and by direct commands
void BM_StepWithLockstepFirmware(benchmark::State& bench) {
  const PluginRegistry registry = Registry();
  auto kernel = WithLink(std::string("native:") + UNIMOUSE_BENCH_FIRMWARE, registry);
  for (auto _ : bench) kernel->Step();
}
BENCHMARK(BM_StepWithLockstepFirmware)->Unit(benchmark::kMicrosecond)->Iterations(20000);

// where the robot ended, as counters: which runs drove alike
void CountEndPose(benchmark::State& bench, Kernel& kernel) {
  const Pose2D pose = kernel.world().RobotPose(kernel.state().data());
  bench.counters["x_m"] = pose.x_m;
  bench.counters["y_m"] = pose.y_m;
}

// per step: the full robot driven by an example firmware in lock-step
void StepWithExample(benchmark::State& bench, const std::string& link, const Maze* maze = nullptr) {
  const PluginRegistry registry = Registry();
  auto kernel = WithLink(link, registry, maze);
  for (auto _ : bench) kernel->Step();
  CountEndPose(bench, *kernel);
}
void BM_StepWithInprocMicromouse(benchmark::State& bench) {
  StepWithExample(bench, "inproc:" UNIMOUSE_FIRMWARE_DIR "/micromouse.so");
}
BENCHMARK(BM_StepWithInprocMicromouse)->Unit(benchmark::kMicrosecond)->Iterations(20000);
// the racer, the main job's firmware: its share of a step (issue 30) beside direct commands
void BM_StepWithInprocRacer(benchmark::State& bench) {
  StepWithExample(bench, "inproc:" UNIMOUSE_FIRMWARE_DIR "/racer.so", Japan2018());
}
BENCHMARK(BM_StepWithInprocRacer)->Unit(benchmark::kMicrosecond)->Iterations(20000);
// the racer's wheel commands after each step of a run of it, replayed as direct commands: the
// same robot driven the same way without the firmware, so that the difference from
// BM_StepWithInprocRacer is the firmware and its link, not a robot that drives otherwise
void BM_StepWithTheRacersCommandsReplayed(benchmark::State& bench) {
  const PluginRegistry registry = Registry();
  std::vector<std::pair<double, double>> commands;
  {
    auto racer = WithLink("inproc:" UNIMOUSE_FIRMWARE_DIR "/racer.so", registry, Japan2018());
    const auto left = racer->model().FindSignal("left.command");
    const auto right = racer->model().FindSignal("right.command");
    for (benchmark::IterationCount i = 0; i < bench.max_iterations; ++i) {
      racer->Step();
      commands.emplace_back(racer->state().signals()[left], racer->state().signals()[right]);
    }
  }
  auto kernel = Kernel::Create(Robot(""), Japan2018(), registry, 1);
  const auto left = kernel->model().FindSignal("left.command");
  const auto right = kernel->model().FindSignal("right.command");
  size_t step = 0;
  for (auto _ : bench) {
    kernel->state().signals()[left] = commands[step].first;
    kernel->state().signals()[right] = commands[step].second;
    ++step;
    kernel->Step();
  }
  CountEndPose(bench, *kernel);
}
BENCHMARK(BM_StepWithTheRacersCommandsReplayed)->Unit(benchmark::kMicrosecond)->Iterations(20000);
void BM_StepWithNativeMicromouse(benchmark::State& bench) {
  StepWithExample(bench, "native:" UNIMOUSE_FIRMWARE_DIR "/micromouse");
}
BENCHMARK(BM_StepWithNativeMicromouse)->Unit(benchmark::kMicrosecond)->Iterations(20000);

void BM_StepWithDirectCommands(benchmark::State& bench) {
  const PluginRegistry registry = Registry();
  auto kernel = Kernel::Create(Robot(""), nullptr, registry, 1);
  kernel->state().signals()[kernel->model().FindSignal("left.command")] = 600;
  kernel->state().signals()[kernel->model().FindSignal("right.command")] = 600;
  for (auto _ : bench) kernel->Step();
}
BENCHMARK(BM_StepWithDirectCommands)->Unit(benchmark::kMicrosecond)->Iterations(20000);

}  // namespace
