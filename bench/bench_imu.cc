// SPDX-License-Identifier: GPL-3.0-or-later
// What the IMU costs a step: the gyro robot's electronics (battery, H-bridges, motors, encoders,
// three ToF sensors, the fan) for 60 simulated seconds in the All Japan 2018 maze at a 1 ms
// step, with and without its ICM-20602 at 1 kHz. The IMU does not act on the world, so both
// runs integrate the very same physics. Their CPU time is measured, a simulated second at a time
// in turn.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <ctime>
#include <filesystem>

#include "bundled_components.h"
#include "kernel.h"

namespace {

using namespace unimouse;

constexpr int kSteps = 60000;

Maze ImuBenchMaze() {
  const std::string path = UNIMOUSE_SHARED_MAZES "/classic/japan2018.txt";
  return LoadMaze(std::filesystem::exists(path)
                      ? path
                      : std::string(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"));
}

// the gyro robot without its trace (file output), and without its IMU unless asked
std::unique_ptr<Kernel> GyroRobot(const Maze& maze, const PluginRegistry& registry, bool imu) {
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse-gyro.yaml");
  std::erase_if(robot.components, [&](const ComponentSpec& c) {
    return c.type == "unimouse.logger" || (!imu && c.type == "unimouse.imu");
  });
  return Kernel::Create(robot, &maze, registry, 1);
}

// CPU seconds of this thread: other processes on a shared host do not count
double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

void Start(Kernel& kernel) {
  kernel.Reset();
  // both H-bridges at 60 % forward: up the first corridor, into the wall, pushing on
  kernel.state().signals()[kernel.model().FindSignal("left.command")] = 614;
  kernel.state().signals()[kernel.model().FindSignal("right.command")] = 614;
}

// runs one simulated second and returns its CPU seconds
double OneSecond(Kernel& kernel) {
  const double start = ThreadCpuSeconds();
  for (int i = 0; i < 1000; ++i) kernel.Step();
  return ThreadCpuSeconds() - start;
}

// the two robots take turns a simulated second at a time, so that whatever else the host does
// falls on both alike; each 60 s run's CPU time is summed, and the fastest of the runs counts
void BM_ImuCostJapan2018(benchmark::State& bench) {
  const Maze maze = ImuBenchMaze();
  PluginRegistry registry;
  AddBundledComponents(registry);
  auto with = GyroRobot(maze, registry, true);
  auto without = GyroRobot(maze, registry, false);
  double with_s = 1e9, without_s = 1e9;
  for (auto _ : bench) {
    Start(*with);
    Start(*without);
    double with_run_s = 0, without_run_s = 0;
    for (int second = 0; second < kSteps / 1000; ++second) {
      with_run_s += OneSecond(*with);
      without_run_s += OneSecond(*without);
    }
    with_s = std::min(with_s, with_run_s);
    without_s = std::min(without_s, without_run_s);
  }
  bench.counters["with_imu_real_time_factor"] = 60 / with_s;
  bench.counters["without_imu_real_time_factor"] = 60 / without_s;
  bench.counters["imu_step_us"] = 1e6 * (with_s - without_s) / kSteps;
  bench.counters["imu_overhead_percent"] = 100 * (with_s / without_s - 1);
}
BENCHMARK(BM_ImuCostJapan2018)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace
