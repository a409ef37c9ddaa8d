// SPDX-License-Identifier: GPL-3.0-or-later
// What a firmware reported about the maze on the link's debug channels (docs/protocol.md, ids
// 10-12), rebuilt from the lines the link logs for them, so that a viewer or a picture can show
// it while the run goes on.
#ifndef UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_
#define UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "maze.h"

namespace unimouse {

struct FirmwareBeliefs {
  /// Side bits as in the protocol: north 1, east 2, south 4, west 8.
  struct CellWalls {
    uint8_t walls = 0;
    uint8_t known = 0;
  };
  std::map<std::pair<int, int>, CellWalls> walls;
  std::vector<Cell> visited;
  std::vector<Cell> path;  ///< the path it last planned

  /// Takes one of the link's debug lines ("debug walls (3, 4): N E; known N E S W", "debug
  /// visited (3, 4)", "debug path (0, 0) (0, 1)"); returns false for any other line.
  bool Read(const std::string& line);
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_
