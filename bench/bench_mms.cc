// SPDX-License-Identifier: GPL-3.0-or-later
// The mms logic tier alone: command lines answered per second, by an in-process left-hand wall
// follower walking All Japan 2018 (a query or two and one motion per step, as mms programs do).
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "maze_generator.h"
#include "mms_protocol.h"

namespace {

using namespace unimouse;

void BM_MmsLogicTierWallFollower(benchmark::State& bench) {
  const std::string path = UNIMOUSE_SHARED_MAZES "/classic/japan2018.txt";
  const Maze maze = std::filesystem::exists(path) ? LoadMaze(path) : GenerateMaze({16, 16, 1, 0});
  MmsWorld world(maze, MmsTiming{});
  long commands = 0;
  auto ask = [&](const char* line) {
    ++commands;
    return world.Handle(line).reply;
  };
  for (auto _ : bench) {
    if (ask("wallLeft") == "false") {
      ask("turnLeft");
    } else {
      while (ask("wallFront") == "true") ask("turnRight");
    }
    benchmark::DoNotOptimize(ask("moveForward"));
  }
  bench.counters["moves_per_s"] =
      benchmark::Counter(double(world.moves()), benchmark::Counter::kIsRate);
  bench.counters["commands_per_s"] =
      benchmark::Counter(double(commands), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_MmsLogicTierWallFollower);

}  // namespace
