// SPDX-License-Identifier: GPL-3.0-or-later
// Shortest paths through a maze whose walls are known (dissertation section 3.4).
//
// - The traditional flood fill counts cells: every move to a neighbouring cell costs 1, turns
//   are free (section 3.4.1).
// - The modified flood fill (algorithm 2) works on robot states (cell, heading): moving one cell
//   forward, turning 90 degrees left and turning 90 degrees right each cost 1, so its costs count
//   turns too (section 3.4.2).
//
// A path's turn-aware cost is its forward moves plus its quarter turns, from the start heading;
// that is the cost tables 5.1-5.4 report for both algorithms. The traditional flood fill leaves
// the choice between equally short neighbours open, and the turns of its path depend on that
// choice: TieRule makes it explicit.
#ifndef UNIMOUSE_MAZETOOLS_MAZE_SOLVER_H_
#define UNIMOUSE_MAZETOOLS_MAZE_SOLVER_H_

#include <cstdint>
#include <string>
#include <vector>

#include "maze.h"

namespace unimouse {

/// A path from a start state to a goal cell.
struct MazePath {
  bool found = false;
  std::vector<Cell> cells;  ///< every cell entered, the start cell first
  int straights = 0;        ///< forward moves of one cell
  int turns = 0;            ///< quarter turns; an about-turn counts 2
  int Cost() const { return straights + turns; }
};

/// Returns the turn-aware cost pieces of a route of neighbouring cells started facing `start`.
MazePath DescribeRoute(const std::vector<Cell>& cells, Heading start);

/// How the traditional flood fill picks among neighbours that are equally near the goal:
/// - "compass:WENS": the first nearer neighbour in a fixed compass order (any order of N, E, S,
///   W). compass:WENS, trying (x-1, y), (x+1, y), (x, y+1), (x, y-1), reproduces the traditional
///   costs of tables 5.3 and 5.4 (118 and 120) and is the default.
/// - "relative:FLRB": an order relative to the current heading: Forward, Left, Right, Back.
/// - "straight:NESW": straight on if that is among the nearest, else the compass order.
struct TieRule {
  enum class Kind { kCompass, kRelative, kStraightThenCompass };
  Kind kind = Kind::kCompass;
  int order[4] = {2, 0, 1, 3};  ///< headings (compass) or turns left of the heading (relative)

  /// Parses a rule; throws InputError naming the forms it accepts.
  static TieRule Parse(const std::string& text);
  std::string Name() const;
};

/// Which sides of every cell can be crossed, for fast repeated solving.
class OpenSides {
 public:
  explicit OpenSides(const Maze& maze);
  int width() const { return width_; }
  int height() const { return height_; }
  bool Open(int cell, int heading) const { return (bits_[cell] >> heading & 1) != 0; }
  int Index(Cell c) const { return c.y * width_ + c.x; }
  Cell CellAt(int index) const { return {index % width_, index / width_}; }
  /// Returns the cell beyond side `heading` of `cell` (only meaningful if it is open).
  int Neighbour(int cell, int heading) const { return cell + step_[heading]; }

 private:
  int width_, height_;
  int step_[4];
  std::vector<uint8_t> bits_;
};

/// The traditional flood fill: cells to the nearest target cell.
class CellFloodFill {
 public:
  static constexpr uint16_t kUnreachable = 0xFFFF;

  /// Computes the distance of every cell to the nearest of `targets`.
  void Compute(const OpenSides& sides, const std::vector<Cell>& targets);
  uint16_t Distance(Cell c) const { return distance_[c.y * width_ + c.x]; }
  /// Follows decreasing distance from `start` facing `heading`, breaking ties by `rule`.
  MazePath PathFrom(const OpenSides& sides, Cell start, Heading heading, const TieRule& rule) const;

 private:
  int width_ = 0;
  std::vector<uint16_t> distance_;
  std::vector<int> queue_;
};

/// The modified flood fill (algorithm 2): actions from every (cell, heading) to a target cell.
class StateFloodFill {
 public:
  static constexpr uint16_t kUnreachable = 0xFFFF;

  /// Computes the cost of every state to the nearest target cell, reached in any heading.
  void Compute(const OpenSides& sides, const std::vector<Cell>& targets);
  uint16_t Cost(Cell c, Heading h) const {
    return cost_[4 * (c.y * width_ + c.x) + static_cast<int>(h)];
  }
  /// Follows decreasing cost from a state; among equal choices: forward, left, right.
  MazePath PathFrom(const OpenSides& sides, Cell start, Heading heading) const;

 private:
  int width_ = 0;
  std::vector<uint16_t> cost_;
  std::vector<int> queue_;
};

}  // namespace unimouse

#endif  // UNIMOUSE_MAZETOOLS_MAZE_SOLVER_H_
