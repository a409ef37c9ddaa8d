// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware_beliefs.h"

namespace unimouse {

bool FirmwareBeliefs::Apply(const unimouse_report& r) {
  switch (r.kind) {
    case UNIMOUSE_REPORT_WALLS:
      walls[{r.x, r.y}] = {static_cast<uint8_t>(r.walls & 0xF),
                           static_cast<uint8_t>(r.known & 0xF)};
      return true;
    case UNIMOUSE_REPORT_VISITED:
      visited.push_back({r.x, r.y});
      return true;
    case UNIMOUSE_REPORT_PATH:
      path.clear();
      for (int i = 0; i < r.ncells && r.cells != nullptr; ++i) {
        path.push_back({r.cells[2 * i], r.cells[2 * i + 1]});
      }
      return true;
    default:
      return false;
  }
}

}  // namespace unimouse
