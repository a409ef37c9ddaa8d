// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as a maze file, in every format: a maze or an InputError, nothing else. A maze that
// is read writes back as text that reads to the same walls.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "maze.h"
#include "unimouse/errors.h"

namespace {

bool SameWalls(const unimouse::Maze& a, const unimouse::Maze& b) {
  if (a.width() != b.width() || a.height() != b.height()) return false;
  for (int y = 0; y <= a.height(); ++y) {
    for (int x = 0; x <= a.width(); ++x) {
      if (x < a.width() && a.HasHorizontalWall(x, y) != b.HasHorizontalWall(x, y)) return false;
      if (y < a.height() && a.HasVerticalWall(x, y) != b.HasVerticalWall(x, y)) return false;
    }
  }
  return true;
}

void Check(unimouse::Maze (*parse)(const std::string&), const std::string& bytes) {
  try {
    const unimouse::Maze maze = parse(bytes);
    const unimouse::Maze again =
        unimouse::ParseMazeText(unimouse::FormatMazeText(maze), "fuzz.txt");
    if (!SameWalls(maze, again)) std::abort();
  } catch (const unimouse::InputError&) {
    // bad input is the expected answer to most bytes
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  Check([](const std::string& b) { return unimouse::ParseMazeText(b, "fuzz.txt"); }, bytes);
  Check([](const std::string& b) { return unimouse::ParseMazeNum(b, "fuzz.num"); }, bytes);
  Check([](const std::string& b) { return unimouse::ParseMazeBinary(b, "fuzz.maz", nullptr); },
        bytes);
  return 0;
}
