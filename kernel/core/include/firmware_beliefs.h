// SPDX-License-Identifier: GPL-3.0-or-later
// What a firmware reported about the maze on the link's debug channels (docs/protocol.md, ids
// 10-12), gathered from the typed reports the link hands the host (unimouse_report), so that a
// viewer, a picture or a maze plot can show it while the run goes on. A program speaking the mms
// protocol fills the same model with its display commands: walls, cell colours and cell texts.
#ifndef UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_
#define UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "maze.h"
#include "unimouse/plugin_abi.h"

namespace unimouse {

/// Most visited cells kept: a firmware that reports more is repeating itself.
inline constexpr size_t kMaxVisitedReports = 1 << 20;
/// Most characters of a cell's text, as mms draws them: two rows of five.
inline constexpr size_t kMaxCellText = 10;

/// An 8-bit RGB colour.
struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8&) const = default;
};

/// Returns the colour of one of mms's colour letters (k b a c g o r w y, the dark B A C G O R Y,
/// and V dark violet; docs/mms.md has the table), or nothing for another character.
std::optional<Rgb8> CellColourOf(char letter);
/// Returns a colour as "#rrggbb".
std::string HexColour(const Rgb8& rgb);
/// Returns the colour letter whose colour (CellColourOf) is `hex`, "#rrggbb", or nothing.
std::optional<char> CellColourLetter(const std::string& hex);

struct FirmwareBeliefs {
  /// Side bits as in the protocol: north 1, east 2, south 4, west 8.
  struct CellWalls {
    uint8_t walls = 0;
    uint8_t known = 0;
  };
  std::map<std::pair<int, int>, CellWalls> walls;
  std::vector<Cell> visited;
  std::vector<Cell> path;                            ///< the path it last planned
  std::map<std::pair<int, int>, char> colours;       ///< a colour letter (CellColourOf) per cell
  std::map<std::pair<int, int>, std::string> texts;  ///< up to kMaxCellText printable characters

  /// Takes one report; returns false for a kind that says nothing about the maze. Cells outside
  /// every maze (beyond kMaxMazeSide_cells) are left out; a path with one is ignored whole.
  bool Apply(const unimouse_report& report);
  /// Whether the firmware reported anything at all.
  bool empty() const {
    return walls.empty() && visited.empty() && path.empty() && colours.empty() && texts.empty();
  }
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_FIRMWARE_BELIEFS_H_
