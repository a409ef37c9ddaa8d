// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware_beliefs.h"

namespace unimouse {
namespace {

// a cell no maze has is a report's mistake, kept out of every picture and route
bool InAnyMaze(int x, int y) {
  return x >= 0 && y >= 0 && x < kMaxMazeSide_cells && y < kMaxMazeSide_cells;
}

}  // namespace

bool FirmwareBeliefs::Apply(const unimouse_report& r) {
  switch (r.kind) {
    case UNIMOUSE_REPORT_WALLS:
      if (InAnyMaze(r.x, r.y)) {
        walls[{r.x, r.y}] = {static_cast<uint8_t>(r.walls & 0xF),
                             static_cast<uint8_t>(r.known & 0xF)};
      }
      return true;
    case UNIMOUSE_REPORT_VISITED:
      if (InAnyMaze(r.x, r.y) && visited.size() < kMaxVisitedReports) {
        visited.push_back({r.x, r.y});
      }
      return true;
    case UNIMOUSE_REPORT_PATH: {
      std::vector<Cell> cells;
      for (int i = 0; i < r.ncells && r.cells != nullptr && i < kMaxMazeSide_cells * 4; ++i) {
        if (!InAnyMaze(r.cells[2 * i], r.cells[2 * i + 1])) return true;
        cells.push_back({r.cells[2 * i], r.cells[2 * i + 1]});
      }
      path = std::move(cells);
      return true;
    }
    default:
      return false;
  }
}

}  // namespace unimouse
