// SPDX-License-Identifier: GPL-3.0-or-later
// Real-time factor of the robot for 60 simulated seconds at a 1 ms step in the All Japan 2018
// maze: the bare mechanics under constant wheel torques (and alone on a floor, for reference),
// and the cost of the whole component chain (battery, H-bridges, motors, encoders, three ToF
// sensors): the full robot drives the maze, then the bare robot replays the very same wheel
// torques, so both runs integrate identical physics and differ only by the components.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>

#include "bundled_components.h"
#include "kernel.h"
#include "maze_generator.h"
#include "unimouse/component.h"

namespace {

using namespace unimouse;

struct ConstantTorqueParams {
  double left_nm = 0;
  double right_nm = 0;
  template <class V>
  void Visit(V& v) {
    v("left_nm", left_nm, "torque on the left wheel");
    v("right_nm", right_nm, "torque on the right wheel");
  }
};

// holds both wheel torques constant: the bench's whole controller
class ConstantTorque final : public Component {
 public:
  static constexpr const char* kTypeName = "bench.constant_torque";
  static constexpr const char* kSummary = "constant wheel torques";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = ConstantTorqueParams;
  explicit ConstantTorque(Params p) : p_(p) {}
  void Bind(BindContext& ctx) override {
    left_ = ctx.ActuatorId("left_motor");
    right_ = ctx.ActuatorId("right_motor");
  }
  void Actuate(const ActuateContext& ctx) const override {
    ctx.mutable_data().ctrl[left_] = p_.left_nm;
    ctx.mutable_data().ctrl[right_] = p_.right_nm;
  }

 private:
  Params p_;
  int left_ = -1, right_ = -1;
};

// wheel torques recorded from the full robot, replayed by the bare one
std::vector<double> recorded_torques;

class ReplayTorque final : public Component {
 public:
  static constexpr const char* kTypeName = "bench.replay_torque";
  static constexpr const char* kSummary = "replays recorded wheel torques";
  static constexpr double kDefaultPeriod_s = 0;
  struct Params {
    template <class V>
    void Visit(V&) {}
  };
  explicit ReplayTorque(Params) {}
  void Bind(BindContext& ctx) override {
    left_ = ctx.ActuatorId("left_motor");
    right_ = ctx.ActuatorId("right_motor");
  }
  void Actuate(const ActuateContext& ctx) const override {
    const size_t i = 2 * static_cast<size_t>(ctx.step());
    ctx.mutable_data().ctrl[left_] = recorded_torques[i];
    ctx.mutable_data().ctrl[right_] = recorded_torques[i + 1];
  }

 private:
  int left_ = -1, right_ = -1;
};

Maze BenchMaze() {
  const std::string path = UNIMOUSE_SHARED_MAZES "/classic/japan2018.txt";
  return LoadMaze(std::filesystem::exists(path)
                      ? path
                      : std::string(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"));
}

PluginRegistry BenchRegistry() {
  PluginRegistry registry;
  registry.AddStatic(ComponentType<ConstantTorque>());
  registry.AddStatic(ComponentType<ReplayTorque>());
  AddBundledComponents(registry);
  return registry;
}

// the full robot, which the benchmarks drive with both H-bridges at 60 % forward: it drives up
// the first corridor, meets the wall and keeps its motors pushing
std::unique_ptr<Kernel> FullRobot(const Maze& maze, const PluginRegistry& registry) {
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  // the electronics only: the trace logger is file output, not part of the chain
  std::erase_if(robot.components,
                [](const ComponentSpec& c) { return c.type == "unimouse.logger"; });
  return Kernel::Create(robot, &maze, registry, 1);
}

void Command(Kernel& kernel, double left, double right) {
  kernel.state().signals()[kernel.model().FindSignal("left.command")] = left;
  kernel.state().signals()[kernel.model().FindSignal("right.command")] = right;
}

constexpr int kSteps = 60000;

// seconds of wall time for one run of `steps` steps (60 s by default) of a kernel from its reset
double TimeRun(Kernel& kernel, double left, double right, int steps = kSteps) {
  kernel.Reset();
  if (kernel.model().FindSignal("left.command") >= 0) Command(kernel, left, right);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) kernel.Step();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// full and bare runs alternate, so that a noisy neighbour slows both alike; the fastest run of
// each is its cost
void BM_ComponentChainCostJapan2018(benchmark::State& bench) {
  const Maze maze = BenchMaze();
  const PluginRegistry registry = BenchRegistry();
  auto full = FullRobot(maze, registry);
  Command(*full, 614, 614);
  recorded_torques.clear();
  for (int i = 0; i < kSteps; ++i) {
    full->Step();
    recorded_torques.push_back(full->state().data().ctrl[0]);
    recorded_torques.push_back(full->state().data().ctrl[1]);
  }
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  robot.components = {
      {"bench.replay_torque", "replay", std::nullopt, ParseYaml("{}", "bench"), {"bench", 1, 1}}};
  auto bare = Kernel::Create(robot, &maze, registry, 1);

  double full_s = 1e9, bare_s = 1e9;
  for (auto _ : bench) {
    full_s = std::min(full_s, TimeRun(*full, 614, 614));
    bare_s = std::min(bare_s, TimeRun(*bare, 0, 0));
  }
  bench.counters["full_real_time_factor"] = 60 / full_s;
  bench.counters["bare_real_time_factor"] = 60 / bare_s;
  bench.counters["chain_overhead_percent"] = 100 * (full_s / bare_s - 1);
}
BENCHMARK(BM_ComponentChainCostJapan2018)->Unit(benchmark::kMillisecond)->Iterations(10);

void RunSixtySeconds(benchmark::State& bench, const Maze* maze) {
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  robot.components.clear();  // the bare mechanics
  // slightly unequal torques: the robot curves, meets walls and keeps pushing along them
  robot.components.push_back({"bench.constant_torque",
                              "drive",
                              std::nullopt,
                              ParseYaml("{left_nm: 0.0010, right_nm: 0.0012}", "bench"),
                              {"bench", 1, 1}});
  const PluginRegistry registry = BenchRegistry();
  auto kernel = Kernel::Create(robot, maze, registry, 1);
  for (auto _ : bench) {
    kernel->Reset();
    for (int i = 0; i < kSteps; ++i) kernel->Step();
  }
  const double sim_s = 60.0 * static_cast<double>(bench.iterations());
  bench.counters["real_time_factor"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
  bench.counters["proxy_overflows"] = static_cast<double>(kernel->world().proxy_overflows());
  const Pose2D pose = kernel->world().RobotPose(kernel->state().data());
  bench.counters["end_x_m"] = pose.x_m;
  bench.counters["end_y_m"] = pose.y_m;
}

void BM_BareRobotJapan2018(benchmark::State& bench) {
  const Maze maze = BenchMaze();
  RunSixtySeconds(bench, &maze);
}
BENCHMARK(BM_BareRobotJapan2018)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BareRobotOpenFloor(benchmark::State& bench) { RunSixtySeconds(bench, nullptr); }
BENCHMARK(BM_BareRobotOpenFloor)->Unit(benchmark::kMillisecond)->UseRealTime();

// the full robot spinning in place in the start cell of a generated maze of `side` cells a side
// (classic dimensions at every size, so that the robot and what its sensors see are the same):
// the real-time factor of 10 simulated seconds, and the seconds the world took to build. With
// the floor's index, neither the proxies nor the rays visit the walls far away: the step costs
// the same at every size
void BM_FullRobotInGeneratedMaze(benchmark::State& bench) {
  GenerateOptions options;
  options.width = options.height = static_cast<int>(bench.range(0));
  options.seed = 1;
  Maze maze = GenerateMaze(options);
  maze.set_class(MazeClass::kClassic);
  const PluginRegistry registry = BenchRegistry();
  const auto start = std::chrono::steady_clock::now();
  auto full = FullRobot(maze, registry);
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double best_s = 1e9;
  for (auto _ : bench) {
    best_s = std::min(best_s, TimeRun(*full, 500, -500, 10000));
  }
  bench.counters["real_time_factor"] = 10 / best_s;
  bench.counters["world_build_s"] = build_s;
  bench.counters["scenery_boxes"] = static_cast<double>(full->world().scenery().size());
}
BENCHMARK(BM_FullRobotInGeneratedMaze)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
