// SPDX-License-Identifier: GPL-3.0-or-later
// Random mazes under the classic rules, for tests and for students: the start cell in the
// south-west corner with a wall on its east side (its exit faces north), the centre cells as the
// goal area with no walls inside and exactly one entrance. A perfect maze (one route between any
// two cells) by default; `loops` removes that fraction of the remaining inner walls.
#ifndef UNIMOUSE_MAZETOOLS_MAZE_GENERATOR_H_
#define UNIMOUSE_MAZETOOLS_MAZE_GENERATOR_H_

#include <cstdint>

#include "maze.h"

namespace unimouse {

struct GenerateOptions {
  int width = 16;
  int height = 16;
  uint64_t seed = 1;
  double loops = 0;  ///< in [0, 1]
};

/// Returns a random maze; the same options give the same maze. Throws InputError for sizes
/// below 3 x 3 or above 255 x 255, or loops outside [0, 1].
Maze GenerateMaze(const GenerateOptions& options);

}  // namespace unimouse

#endif  // UNIMOUSE_MAZETOOLS_MAZE_GENERATOR_H_
