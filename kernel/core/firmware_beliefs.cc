// SPDX-License-Identifier: GPL-3.0-or-later
#include "firmware_beliefs.h"

#include <cstdio>
#include <string_view>

namespace unimouse {
namespace {

// a cell no maze has is a report's mistake, kept out of every picture and route
bool InAnyMaze(int x, int y) {
  return x >= 0 && y >= 0 && x < kMaxMazeSide_cells && y < kMaxMazeSide_cells;
}

}  // namespace

std::string HexColour(const Rgb8& rgb) {
  char hex[8];
  std::snprintf(hex, sizeof(hex), "#%02x%02x%02x", rgb.r, rgb.g, rgb.b);
  return hex;
}

std::optional<char> CellColourLetter(const std::string& hex) {
  for (char letter : std::string_view("kbacgorwyBACGORYV")) {
    if (HexColour(*CellColourOf(letter)) == hex) return letter;
  }
  return std::nullopt;
}

// the saturated colours full, the dark ones at half
std::optional<Rgb8> CellColourOf(char letter) {
  switch (letter) {
    case 'k':
      return Rgb8{0, 0, 0};
    case 'b':
      return Rgb8{0, 0, 255};
    case 'a':
      return Rgb8{160, 160, 160};
    case 'c':
      return Rgb8{0, 255, 255};
    case 'g':
      return Rgb8{0, 255, 0};
    case 'o':
      return Rgb8{255, 165, 0};
    case 'r':
      return Rgb8{255, 0, 0};
    case 'w':
      return Rgb8{255, 255, 255};
    case 'y':
      return Rgb8{255, 255, 0};
    case 'B':
      return Rgb8{0, 0, 128};
    case 'A':
      return Rgb8{96, 96, 96};
    case 'C':
      return Rgb8{0, 128, 128};
    case 'G':
      return Rgb8{0, 128, 0};
    case 'O':
      return Rgb8{200, 100, 0};
    case 'R':
      return Rgb8{128, 0, 0};
    case 'Y':
      return Rgb8{128, 128, 0};
    case 'V':
      return Rgb8{128, 0, 128};
    default:
      return std::nullopt;
  }
}

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
