// SPDX-License-Identifier: GPL-3.0-or-later
// Real-time factor of the bare robot (no motor models) driving with constant wheel torques for
// 60 simulated seconds at a 1 ms step: in the All Japan 2018 maze, and alone on a floor.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "kernel.h"
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

void RunSixtySeconds(benchmark::State& bench, const Maze* maze) {
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  robot.components.clear();  // the bare mechanics
  // slightly unequal torques: the robot curves, meets walls and keeps pushing along them
  robot.components.push_back({"bench.constant_torque",
                              "drive",
                              std::nullopt,
                              ParseYaml("{left_nm: 0.0010, right_nm: 0.0012}", "bench"),
                              {"bench", 1, 1}});
  PluginRegistry registry;
  registry.AddStatic(ComponentType<ConstantTorque>());
  auto kernel = Kernel::Create(robot, maze, registry, 1);
  const int steps = 60000;
  for (auto _ : bench) {
    kernel->Reset();
    for (int i = 0; i < steps; ++i) kernel->Step();
  }
  const double sim_s = 60.0 * static_cast<double>(bench.iterations());
  bench.counters["real_time_factor"] = benchmark::Counter(sim_s, benchmark::Counter::kIsRate);
  bench.counters["proxy_overflows"] = static_cast<double>(kernel->world().proxy_overflows());
  const Pose2D pose = kernel->world().RobotPose(kernel->state().data());
  bench.counters["end_x_m"] = pose.x_m;
  bench.counters["end_y_m"] = pose.y_m;
}

void BM_BareRobotJapan2018(benchmark::State& bench) {
  const std::string path = UNIMOUSE_SHARED_MAZES "/classic/japan2018.txt";
  const Maze maze = LoadMaze(std::filesystem::exists(path)
                                 ? path
                                 : std::string(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt"));
  RunSixtySeconds(bench, &maze);
}
BENCHMARK(BM_BareRobotJapan2018)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_BareRobotOpenFloor(benchmark::State& bench) { RunSixtySeconds(bench, nullptr); }
BENCHMARK(BM_BareRobotOpenFloor)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
