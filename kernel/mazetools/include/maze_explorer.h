// SPDX-License-Identifier: GPL-3.0-or-later
// Adachi method 0 exploration (dissertation section 3.4.3), logic-level: a mouse that senses the
// four walls of every cell it enters, plans with the modified flood fill over the walls it knows
// (unknown walls open), runs start -> goal -> start -> ..., and stops at the end of the trip after
// which the open path (unknown walls open) and the closed path (unknown walls closed) from the
// start cost the same: then no unexplored route can beat the known one.
#ifndef UNIMOUSE_MAZETOOLS_MAZE_EXPLORER_H_
#define UNIMOUSE_MAZETOOLS_MAZE_EXPLORER_H_

#include <vector>

#include "maze.h"
#include "maze_solver.h"

namespace unimouse {

struct ExploreOptions {
  double cell_time_s = 0.5;  ///< estimated time to move one cell
  double turn_time_s = 0.5;  ///< estimated time to turn 90 degrees
  int max_trips = 40;
};

/// What the mouse knows: walls it has seen, and which sides it has seen at all.
class WallKnowledge {
 public:
  explicit WallKnowledge(const Maze& truth);
  /// Records the four sides of `c` as they are in the true maze; returns whether anything new
  /// was learnt.
  bool Sense(const Maze& truth, Cell c);
  bool Known(Cell c, Heading h) const;
  bool Visited(Cell c) const { return visited_[Index(c)] != 0; }
  int VisitedCount() const;
  /// The maze with unknown walls taken as open.
  const Maze& OpenView() const { return open_view_; }
  /// The maze with unknown walls taken as closed.
  Maze ClosedView() const;

 private:
  int Index(Cell c) const { return c.y * open_view_.width() + c.x; }
  Maze open_view_;
  std::vector<uint8_t> known_sides_;  // bit per heading
  std::vector<uint8_t> visited_;
};

struct TripRecord {
  int trip = 0;           ///< from 1
  bool to_goal = true;    ///< odd trips go to the goal, even trips home
  int open_cost = -1;     ///< start -> goal, unknown walls open; -1 when there is no path
  int closed_cost = -1;   ///< start -> goal, unknown walls closed; -1 when there is no path
  int cells_visited = 0;  ///< cells explored so far
  int forward_moves = 0;  ///< this trip
  int turns = 0;          ///< this trip, quarter turns
  double time_s = 0;      ///< this trip, by the options' time model
  MazePath open_path;
  MazePath closed_path;
  std::vector<Cell> route;  ///< cells this trip entered, its first cell first
};

struct Exploration {
  std::vector<TripRecord> trips;
  std::vector<WallKnowledge> knowledge;  ///< what the mouse knew after each trip
  bool optimal_found = false;            ///< open and closed costs matched
  bool goal_unreachable = false;
  MazePath best;                 ///< the closed path after the last trip
  std::vector<uint8_t> visited;  ///< per cell, row by row from the south-west
};

/// Explores `truth` from its start state until the best path is known, or the trip limit.
Exploration ExploreAdachi(const Maze& truth, const ExploreOptions& options = {});

}  // namespace unimouse

#endif  // UNIMOUSE_MAZETOOLS_MAZE_EXPLORER_H_
