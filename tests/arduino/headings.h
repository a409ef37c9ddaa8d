// SPDX-License-Identifier: GPL-3.0-or-later
// Between the simulator's maze headings and the firmware library's directions, for tests that
// feed one from the other.
#ifndef UNIMOUSE_TESTS_ARDUINO_HEADINGS_H_
#define UNIMOUSE_TESTS_ARDUINO_HEADINGS_H_

#include "Maze.h"
#include "maze.h"

namespace unimouse {

inline constexpr Heading kHeadingOf[4] = {Heading::kNorth, Heading::kEast, Heading::kSouth,
                                          Heading::kWest};  // by Direction

inline Heading ToHeading(Direction d) { return kHeadingOf[static_cast<int>(d)]; }

inline Direction ToDirection(Heading h) {
  for (int d = 0; d < 4; ++d) {
    if (kHeadingOf[d] == h) return static_cast<Direction>(d);
  }
  return Direction::North;
}

}  // namespace unimouse

#endif  // UNIMOUSE_TESTS_ARDUINO_HEADINGS_H_
