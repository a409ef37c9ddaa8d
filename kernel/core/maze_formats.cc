// SPDX-License-Identifier: GPL-3.0-or-later
// The mms .num format, binary .maz files, and telling the formats apart by content.
#include <algorithm>
#include <cctype>
#include <optional>
#include <sstream>

#include "maze.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

// per-cell wall bits in our heading order: east, north, west, south
using CellWalls = std::vector<uint8_t>;

bool Bit(uint8_t walls, Heading h) { return (walls >> static_cast<int>(h) & 1) != 0; }

Cell Beyond(Cell c, Heading h) {
  const int i = static_cast<int>(h);
  return {c.x + (i == 0) - (i == 2), c.y + (i == 1) - (i == 3)};
}

Heading Opposite(Heading h) { return static_cast<Heading>((static_cast<int>(h) + 2) & 3); }

// the first shared wall recorded on one side only, or nullopt
struct Mismatch {
  Cell cell;
  Heading side;
};
std::optional<Mismatch> FirstOneSided(const CellWalls& walls, int w, int h) {
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (Heading side : {Heading::kEast, Heading::kNorth}) {
        const Cell n = Beyond({x, y}, side);
        if (n.x >= w || n.y >= h) continue;
        if (Bit(walls[y * w + x], side) != Bit(walls[n.y * w + n.x], Opposite(side))) {
          return Mismatch{{x, y}, side};
        }
      }
    }
  }
  return std::nullopt;
}

bool ClosedPerimeter(const CellWalls& walls, int w, int h) {
  for (int x = 0; x < w; ++x) {
    if (!Bit(walls[x], Heading::kSouth) || !Bit(walls[(h - 1) * w + x], Heading::kNorth)) {
      return false;
    }
  }
  for (int y = 0; y < h; ++y) {
    if (!Bit(walls[y * w], Heading::kWest) || !Bit(walls[y * w + w - 1], Heading::kEast)) {
      return false;
    }
  }
  return true;
}

Maze FromCellWalls(const CellWalls& walls, int w, int h) {
  Maze maze(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int side = 0; side < 4; ++side) {
        if (walls[y * w + x] >> side & 1) maze.SetWall({x, y}, static_cast<Heading>(side), true);
      }
    }
  }
  return maze;
}

const char* kSideNames[] = {"east", "north", "west", "south"};

std::string CellText(Cell c) {
  return "cell (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ")";
}

}  // namespace

Maze ParseMazeNum(const std::string& text, const std::string& file) {
  struct Entry {
    int x, y;
    uint8_t walls;
    int line;
  };
  std::vector<Entry> entries;
  std::istringstream in(text);
  std::string line;
  int w = 0, h = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    std::istringstream fields(line);
    int v[6];
    for (int i = 0; i < 6; ++i) {
      if (!(fields >> v[i]) || (i >= 2 && v[i] != 0 && v[i] != 1) || (i < 2 && v[i] < 0)) {
        throw InputError(file + ":" + std::to_string(number) + ":1: expected 'X Y N E S W': " +
                         "two cell coordinates from 0, then 0 or 1 for each wall");
      }
    }
    std::string extra;
    if (fields >> extra) {
      throw InputError(file + ":" + std::to_string(number) + ":1: more than six numbers");
    }
    if (v[0] >= kMaxMazeSide_cells || v[1] >= kMaxMazeSide_cells) {
      CheckMazeSize(int64_t{v[0]} + 1, int64_t{v[1]} + 1,
                    file + ":" + std::to_string(number) + ":1");
    }
    // N E S W in the file; east, north, west, south here
    const uint8_t walls = static_cast<uint8_t>(v[3] << 0 | v[2] << 1 | v[5] << 2 | v[4] << 3);
    entries.push_back({v[0], v[1], walls, number});
    w = std::max(w, v[0] + 1);
    h = std::max(h, v[1] + 1);
  }
  UNIMOUSE_THROW_UNLESS(!entries.empty(), file + ": no cells: not a .num maze");

  CellWalls walls(static_cast<size_t>(w) * static_cast<size_t>(h), 0);
  std::vector<int> defined_at(walls.size(), 0);
  for (const Entry& e : entries) {
    int& at = defined_at[e.y * w + e.x];
    if (at != 0) {
      throw InputError(file + ":" + std::to_string(e.line) + ":1: " + CellText({e.x, e.y}) +
                       " is given twice (first at line " + std::to_string(at) + ")");
    }
    at = e.line;
    walls[e.y * w + e.x] = e.walls;
  }
  for (int i = 0; i < w * h; ++i) {
    if (defined_at[i] == 0) {
      throw InputError(file + ": " + CellText({i % w, i / w}) + " is missing: a .num maze lists " +
                       std::to_string(w) + " x " + std::to_string(h) + " cells");
    }
  }
  if (const auto m = FirstOneSided(walls, w, h)) {
    const Cell n = Beyond(m->cell, m->side);
    const bool here = Bit(walls[m->cell.y * w + m->cell.x], m->side);
    const Cell has = here ? m->cell : n;
    const Cell lacks = here ? n : m->cell;
    const Heading side = here ? m->side : Opposite(m->side);
    throw InputError(file + ":" + std::to_string(defined_at[has.y * w + has.x]) +
                     ":1: " + CellText(has) + " has a " + kSideNames[static_cast<int>(side)] +
                     " wall that " + CellText(lacks) + " (line " +
                     std::to_string(defined_at[lacks.y * w + lacks.x]) +
                     ") does not record: walls must be recorded on both sides");
  }
  Maze maze = FromCellWalls(walls, w, h);
  FaceStartTowardsItsExit(maze);
  return maze;
}

Maze ParseMazeBinary(const std::string& bytes, const std::string& file, std::string* layout) {
  // one byte a cell: more bytes than the largest maze has cells is no maze we read
  const int64_t most = int64_t{kMaxMazeSide_cells} * kMaxMazeSide_cells;
  if (static_cast<int64_t>(bytes.size()) > most) {
    throw InputError(file + ": " + std::to_string(bytes.size()) +
                     " bytes is more than a binary maze of at most " +
                     std::to_string(kMaxMazeSide_cells) + " x " +
                     std::to_string(kMaxMazeSide_cells) + " cells has (docs/limits.md)");
  }
  int side = 0;
  while (side * side < static_cast<int>(bytes.size())) ++side;
  UNIMOUSE_THROW_UNLESS(side * side == static_cast<int>(bytes.size()) && side >= 2,
                        file + ": a binary maze has one byte per cell of a square maze; " +
                            std::to_string(bytes.size()) + " bytes is not a square");

  // bit b of a byte means the wall on side perm[b] (east, north, west, south numbering); the
  // byte at index i is the cell that one of the eight symmetries of the square puts there
  static const char* kLetters = "ENWS";
  std::vector<int> perm = {1, 0, 3, 2};  // the standard: N=1 E=2 S=4 W=8
  const std::vector<int> standard = perm;
  std::sort(perm.begin(), perm.end());
  std::string best_description;
  std::optional<CellWalls> best;
  int best_rank = 1 << 30;
  for (int symmetry = 0; symmetry < 8; ++symmetry) {
    do {
      CellWalls walls(bytes.size(), 0);
      for (int i = 0; i < static_cast<int>(bytes.size()); ++i) {
        const unsigned char byte = static_cast<unsigned char>(bytes[static_cast<size_t>(i)]);
        // the standard: x = i div n, y = i mod n; the symmetries swap and mirror the axes
        int x = i / side, y = i % side;
        if (symmetry & 1) std::swap(x, y);
        if (symmetry & 2) x = side - 1 - x;
        if (symmetry & 4) y = side - 1 - y;
        uint8_t w = 0;
        for (int b = 0; b < 4; ++b) {
          if (byte >> b & 1) w |= static_cast<uint8_t>(1 << perm[b]);
        }
        walls[y * side + x] = w;
      }
      const uint8_t start = walls[0];
      const bool classic_start = Bit(start, Heading::kEast) && !Bit(start, Heading::kNorth);
      if (!FirstOneSided(walls, side, side) && ClosedPerimeter(walls, side, side) &&
          classic_start) {
        // prefer the standard layout, then the standard bit order, then anything
        const int rank = (symmetry != 0) * 2 + (perm != standard);
        if (rank < best_rank) {
          best_rank = rank;
          best = walls;
          best_description = "binary .maz, ";
          best_description += symmetry == 0 ? "column-major from the south-west"
                                            : "layout " + std::to_string(symmetry) + " of 8";
          best_description += ", bits";
          for (int b = 0; b < 4; ++b) {
            best_description += std::string(" ") + kLetters[perm[b]] + "=" + std::to_string(1 << b);
          }
        }
      }
    } while (std::next_permutation(perm.begin(), perm.end()));
  }
  if (!best) {
    throw InputError(file +
                     ": no layout or bit order of this binary maze gives consistent walls, "
                     "a closed perimeter and a south-west start with its exit north");
  }
  if (layout != nullptr) *layout = best_description;
  return FromCellWalls(*best, side, side);
}

Maze LoadMaze(const std::string& path, std::string* format) {
  const std::string content = ReadTextFile(path);
  std::string found = "text";
  Maze maze = [&] {
    // binary: control bytes no text has; every real maze has such cells (the classic start,
    // 0x0e). Bytes from 0x80 up are not a sign: text may carry UTF-8 or Latin-1 in its notes
    const bool binary = std::any_of(content.begin(), content.end(), [](char c) {
      const auto b = static_cast<unsigned char>(c);
      return b < 0x20 && c != '\t' && c != '\r' && c != '\n';
    });
    if (binary) return ParseMazeBinary(content, path, &found);
    // .num: the first line is six numbers
    const size_t first = content.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && std::isdigit(static_cast<unsigned char>(content[first]))) {
      found = "num";
      return ParseMazeNum(content, path);
    }
    return ParseMazeText(content, path);
  }();
  if (format != nullptr) *format = found;
  return maze;
}

}  // namespace unimouse
