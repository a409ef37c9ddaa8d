// SPDX-License-Identifier: GPL-3.0-or-later
// The maze module alone: one full modified flood fill (algorithm 2) on 16 x 16 and 32 x 32
// contest mazes, the traditional flood fill for comparison, and Adachi exploration of every
// solvable maze of the contest collection end to end.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>
#include <vector>

#include "maze_explorer.h"
#include "maze_generator.h"
#include "maze_solver.h"

namespace {

using namespace unimouse;

const std::string kShared = UNIMOUSE_SHARED_MAZES;

// a contest maze from the collection, or a generated one of the same size without it
Maze ContestMaze(const std::string& file, int size) {
  const std::string path = kShared + "/" + file;
  if (std::filesystem::exists(path)) return LoadMaze(path);
  return GenerateMaze({size, size, 1, 0});
}

void ModifiedFloodFill(benchmark::State& bench, const Maze& maze) {
  const OpenSides sides(maze);
  StateFloodFill fill;
  for (auto _ : bench) {
    fill.Compute(sides, maze.goals());
    benchmark::DoNotOptimize(fill.Cost(maze.start(), maze.start_heading()));
  }
}

void BM_ModifiedFloodFill16x16(benchmark::State& bench) {
  ModifiedFloodFill(bench, ContestMaze("classic/japan2018.txt", 16));
}
BENCHMARK(BM_ModifiedFloodFill16x16)->Unit(benchmark::kMicrosecond);

void BM_ModifiedFloodFill32x32(benchmark::State& bench) {
  ModifiedFloodFill(bench, ContestMaze("halfsize/japan2018hef.txt", 32));
}
BENCHMARK(BM_ModifiedFloodFill32x32)->Unit(benchmark::kMicrosecond);

// the same including the table of open sides, as after every newly seen wall
void BM_ModifiedFloodFillWithWallTable32x32(benchmark::State& bench) {
  const Maze maze = ContestMaze("halfsize/japan2018hef.txt", 32);
  StateFloodFill fill;
  for (auto _ : bench) {
    const OpenSides sides(maze);
    fill.Compute(sides, maze.goals());
    benchmark::DoNotOptimize(fill.Cost(maze.start(), maze.start_heading()));
  }
}
BENCHMARK(BM_ModifiedFloodFillWithWallTable32x32)->Unit(benchmark::kMicrosecond);

void BM_TraditionalFloodFill32x32(benchmark::State& bench) {
  const Maze maze = ContestMaze("halfsize/japan2018hef.txt", 32);
  const OpenSides sides(maze);
  CellFloodFill fill;
  for (auto _ : bench) {
    fill.Compute(sides, maze.goals());
    benchmark::DoNotOptimize(fill.Distance(maze.start()));
  }
}
BENCHMARK(BM_TraditionalFloodFill32x32)->Unit(benchmark::kMicrosecond);

void BM_ExploreEverySolvableMazeOfTheCollection(benchmark::State& bench) {
  if (!std::filesystem::is_directory(kShared)) {
    bench.SkipWithError("the maze collection (../shared/mazes) is not beside the project");
    return;
  }
  std::vector<Maze> mazes;
  for (const auto& e : std::filesystem::recursive_directory_iterator(kShared)) {
    if (e.path().extension() != ".txt") continue;
    Maze maze = LoadMaze(e.path().string());
    const OpenSides sides(maze);
    CellFloodFill fill;
    fill.Compute(sides, maze.goals());
    if (fill.Distance(maze.start()) != CellFloodFill::kUnreachable)
      mazes.push_back(std::move(maze));
  }
  int proven = 0;
  for (auto _ : bench) {
    proven = 0;
    for (const Maze& maze : mazes) proven += ExploreAdachi(maze).optimal_found ? 1 : 0;
  }
  bench.counters["mazes"] = static_cast<double>(mazes.size());
  bench.counters["proven_optimal"] = proven;
}
BENCHMARK(BM_ExploreEverySolvableMazeOfTheCollection)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
