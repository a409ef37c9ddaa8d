// SPDX-License-Identifier: GPL-3.0-or-later
// A whole run through Session, as the command line makes it: the speed-control challenge with
// its Lua controller (scenario, robot, pictures off), reported as a real-time factor.
#include "bench_session.h"

#include <filesystem>

#include "bundled_components.h"

namespace unimouse {

void RunSessionBenchmark(benchmark::State& bench, SessionOptions options) {
  PluginRegistry registry;
  AddBundledComponents(registry);
  options.registry = &registry;
  options.out_dir = (std::filesystem::temp_directory_path() / "unimouse-bench-session").string();
  options.only_asked_pictures = true;
  options.console = false;
  for (auto _ : bench) {
    std::unique_ptr<Session> session = Session::Open(options);
    while (!session->Over()) session->Step();
    const RunRecord record = session->Finish();
    bench.counters["real_time_factor"] = record.real_time_factor;
    bench.counters["sim_time_s"] = record.sim_time_s;
    bench.counters["us_per_step"] = 1e6 * record.wall_time_s / static_cast<double>(record.steps);
  }
  // the size of the recording, where the run made one
  const std::filesystem::path recording = std::filesystem::path(options.out_dir) / "run.mcap";
  bench.counters["mcap_MB"] = std::filesystem::exists(recording)
                                  ? static_cast<double>(std::filesystem::file_size(recording)) / 1e6
                                  : 0.0;
  std::filesystem::remove_all(options.out_dir);
}

namespace {

void BM_SessionSpeedControlScenario(benchmark::State& bench) {
  SessionOptions options;
  options.scenario = UNIMOUSE_SOURCE_DIR "/scenarios/speed_control.lua";
  options.controller = UNIMOUSE_SOURCE_DIR "/tests/scenarios/speed_controller.lua";
  RunSessionBenchmark(bench, options);
}
BENCHMARK(BM_SessionSpeedControlScenario)->Unit(benchmark::kMillisecond)->Iterations(3);

// the main job as `unimouse run` makes it (the contest in All Japan 2018 with the bundled
// racer firmware in-process), without its pictures: to set beside BM_BareRobotJapan2018,
// the same maze's physics alone
SessionOptions MainJob() {
  SessionOptions options;
  options.scenario = "micromouse";
  options.sets = {"end_on_log=done"};
  options.link = "inproc:" UNIMOUSE_FIRMWARE_DIR "/racer.so";
  return options;
}

void BM_MainJobJapan2018(benchmark::State& bench) { RunSessionBenchmark(bench, MainJob()); }
BENCHMARK(BM_MainJobJapan2018)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

// the main job with its recording off, light (the default) and full: what recording costs in
// wall time, and the size of run.mcap (docs/performance.md, "Recording")
void BM_MainJobRecording(benchmark::State& bench) {
  const char* levels[] = {"off", "light", "full"};
  SessionOptions options = MainJob();
  options.record = levels[bench.range(0)];
  bench.SetLabel(options.record);
  RunSessionBenchmark(bench, options);
}
BENCHMARK(BM_MainJobRecording)
    ->Arg(0)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->UseRealTime();

// a step with one full robot (its components, the bundled firmware in-process, in lock-step)
// exploring All Japan 2018, and with two: the second from the opposite corner, its own copy of
// the firmware. Set side by side: us_per_step of the two against that of the one
void BM_OneFullRobotStepJapan2018(benchmark::State& bench) {
  SessionOptions options;
  options.maze = "japan2018";
  options.duration_s = 30;
  options.link = "inproc:" UNIMOUSE_FIRMWARE_DIR "/micromouse.so";
  RunSessionBenchmark(bench, options);
}
BENCHMARK(BM_OneFullRobotStepJapan2018)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5)
    ->UseRealTime();

void BM_TwoFullRobotsStepJapan2018(benchmark::State& bench) {
  SessionOptions options;
  options.maze = "japan2018";
  options.duration_s = 30;
  const std::string link = "inproc:" UNIMOUSE_FIRMWARE_DIR "/micromouse.so";
  options.robots = {{"unimouse", "", link, {}, "", "", ""},
                    {"unimouse", "", link, {}, "", "", "15,15,S"}};
  RunSessionBenchmark(bench, options);
}
BENCHMARK(BM_TwoFullRobotsStepJapan2018)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5)
    ->UseRealTime();

}  // namespace
}  // namespace unimouse
