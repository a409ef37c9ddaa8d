// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures: the time of one 640x480 snapshot of the robot in the All Japan 2018 maze (drawing
// and reading back, then also writing the PNG), and the real-time factor of 60 simulated
// seconds of the full robot with and without a snapshot every simulated second. On a machine
// without EGL the benchmarks say so and skip.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

#include "bundled_components.h"
#include "egl_context.h"
#include "kernel.h"
#include "png_file.h"
#include "run_pictures.h"
#include "scene_renderer.h"

namespace {

using namespace unimouse;

struct Rig {
  Maze maze = LoadMaze(UNIMOUSE_SOURCE_DIR "/mazes/japan2018.txt");
  RobotSpec robot = LoadRobotSpec(UNIMOUSE_SOURCE_DIR "/robots/unimouse.yaml");
  PluginRegistry registry;
  std::unique_ptr<Kernel> kernel;
  Rig() {
    std::erase_if(robot.components,
                  [](const ComponentSpec& c) { return c.type == "unimouse.logger"; });
    AddBundledComponents(registry);
    kernel = Kernel::Create(robot, &maze, registry, 1);
    kernel->Step();
  }
};

std::unique_ptr<EglContext> ContextOrSkip(benchmark::State& bench) {
  try {
    return EglContext::Create();
  } catch (const RenderUnavailable& e) {
    bench.SkipWithError(e.what());
    return nullptr;
  }
}

void BM_Snapshot640x480(benchmark::State& bench) {
  Rig rig;
  auto egl = ContextOrSkip(bench);
  if (!egl) return;
  SceneRenderer renderer(*rig.kernel);
  const DrawOptions draw{.hud = {"run 1  best -", "time 12.3 s of 600 s"}};
  for (auto _ : bench) benchmark::DoNotOptimize(renderer.Snapshot(640, 480, "top", draw));
  bench.SetLabel(egl->renderer());
}
BENCHMARK(BM_Snapshot640x480)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Snapshot640x480Png(benchmark::State& bench) {
  Rig rig;
  auto egl = ContextOrSkip(bench);
  if (!egl) return;
  SceneRenderer renderer(*rig.kernel);
  const std::string file = (std::filesystem::temp_directory_path() / "unimouse-bench.png").string();
  for (auto _ : bench) {
    const Image image = renderer.Snapshot(640, 480, "top", {});
    WritePng(file, image.width, image.height, image.rgb);
  }
  std::filesystem::remove(file);
}
BENCHMARK(BM_Snapshot640x480Png)->Unit(benchmark::kMillisecond)->UseRealTime();

// 60 s of the full robot at rest in its start cell; range(0): seconds between snapshots, 0 none
void BM_RealTimeFactorWithSnapshots(benchmark::State& bench) {
  const std::string out =
      (std::filesystem::temp_directory_path() / "unimouse-bench-pictures").string();
  for (auto _ : bench) {
    Rig rig;
    PictureOptions options;
    options.every_s = static_cast<double>(bench.range(0));
    std::unique_ptr<RunPictures> pictures;
    try {
      pictures = std::make_unique<RunPictures>(*rig.kernel, options, nullptr, out);
    } catch (const RenderUnavailable& e) {
      bench.SkipWithError(e.what());
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    while (rig.kernel->state().data().time < 60) {
      rig.kernel->Step();
      pictures->AfterStep();
    }
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    bench.counters["real_time_factor"] = 60 / wall_s;
    bench.counters["pictures"] = pictures->written();
  }
  std::filesystem::remove_all(out);
}
BENCHMARK(BM_RealTimeFactorWithSnapshots)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3)
    ->UseRealTime();

}  // namespace
