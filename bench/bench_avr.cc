// SPDX-License-Identifier: GPL-3.0-or-later
// The emulated board's speed: the wall-distance example's Mega 2560 image (the one to flash) on
// its own, fed the link's byte stream (encoder frames every 1 ms step, ToF frames every 30 ms),
// as emulated MHz and real-time factor on this host; then the whole challenge through Session
// with --link avr:, as the command line runs it.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "avr_board.h"
#include "bench_session.h"

namespace {

using namespace unimouse;

const std::string kImage = UNIMOUSE_BINARY_DIR "/avr/wall_distance.elf";

void BM_AvrBoardWallDistanceImage(benchmark::State& bench) {
  if (!std::filesystem::exists(kImage)) {
    bench.SkipWithError("no AVR build of the examples (gcc-avr, arduino-core-avr)");
    return;
  }
  const std::vector<uint8_t> encoders = {3, 2, 0, 4, 2, 0};
  const std::vector<uint8_t> tof = {0, 0x40, 0x1F, 1, 0xFF, 0xFF, 2, 0x00, 0x80};
  for (auto _ : bench) {
    link::AvrBoard board(kImage, {});
    std::vector<uint8_t> out;
    // 10 s of emulated time, step by step as the link runs it
    for (uint64_t ms = 0; ms < 10000; ++ms) {
      board.Write(encoders);
      if (ms % 30 == 0) board.Write(tof);
      if (!board.RunUntil((ms + 1) * 16000).empty()) bench.SkipWithError("the firmware stopped");
      board.Read(out);
      out.clear();
    }
    const link::AvrBoardStats s = board.stats();
    bench.counters["emulated_mhz"] = s.emulated_mhz();
    bench.counters["real_time_factor"] = s.emulated_s() / s.host_cpu_s;
    bench.counters["mips"] = static_cast<double>(s.instructions) / s.host_cpu_s / 1e6;
  }
}
BENCHMARK(BM_AvrBoardWallDistanceImage)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_AvrSessionWallDistanceScenario(benchmark::State& bench) {
  if (!std::filesystem::exists(kImage)) {
    bench.SkipWithError("no AVR build of the examples (gcc-avr, arduino-core-avr)");
    return;
  }
  SessionOptions options;
  options.scenario = UNIMOUSE_SOURCE_DIR "/scenarios/wall_distance.lua";
  options.link = "avr:" + kImage;
  RunSessionBenchmark(bench, options);
}
BENCHMARK(BM_AvrSessionWallDistanceScenario)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
