// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze_explorer.h"

namespace unimouse {
namespace {

int BestCost(const Maze& view, const Maze& truth, MazePath* path) {
  const OpenSides sides(view);
  StateFloodFill fill;
  fill.Compute(sides, truth.goals());
  *path = fill.PathFrom(sides, truth.start(), truth.start_heading());
  return path->found ? path->Cost() : -1;
}

}  // namespace

WallKnowledge::WallKnowledge(const Maze& truth)
    : open_view_(truth.width(), truth.height()),
      known_sides_(static_cast<size_t>(truth.width() * truth.height()), 0),
      visited_(known_sides_.size(), 0) {
  open_view_.set_start(truth.start(), truth.start_heading());
  open_view_.set_goals(truth.goals());
}

bool WallKnowledge::Known(Cell c, Heading h) const {
  return (known_sides_[Index(c)] >> static_cast<int>(h) & 1) != 0;
}

bool WallKnowledge::Sense(const Maze& truth, Cell c) {
  visited_[Index(c)] = 1;
  bool learnt = false;
  for (int h = 0; h < 4; ++h) {
    const Heading heading = static_cast<Heading>(h);
    if (Known(c, heading)) continue;
    learnt = true;
    known_sides_[Index(c)] |= static_cast<uint8_t>(1 << h);
    const int dx = (h == 0) - (h == 2), dy = (h == 1) - (h == 3);
    const Cell n{c.x + dx, c.y + dy};
    if (open_view_.Contains(n)) known_sides_[Index(n)] |= static_cast<uint8_t>(1 << ((h + 2) & 3));
    if (truth.HasWall(c, heading)) open_view_.SetWall(c, heading, true);
  }
  return learnt;
}

int WallKnowledge::VisitedCount() const {
  int n = 0;
  for (uint8_t v : visited_) n += v;
  return n;
}

Maze WallKnowledge::ClosedView() const {
  Maze closed = open_view_;
  for (int y = 0; y < closed.height(); ++y) {
    for (int x = 0; x < closed.width(); ++x) {
      for (int h = 0; h < 4; ++h) {
        if (!Known({x, y}, static_cast<Heading>(h)))
          closed.SetWall({x, y}, static_cast<Heading>(h), true);
      }
    }
  }
  return closed;
}

Exploration ExploreAdachi(const Maze& truth, const ExploreOptions& options) {
  Exploration out;
  WallKnowledge knowledge(truth);
  Cell cell = truth.start();
  int heading = static_cast<int>(truth.start_heading());
  knowledge.Sense(truth, cell);

  for (int trip = 1; trip <= options.max_trips; ++trip) {
    TripRecord record;
    record.trip = trip;
    record.to_goal = trip % 2 == 1;
    const std::vector<Cell> targets =
        record.to_goal ? truth.goals() : std::vector<Cell>{truth.start()};
    record.route.push_back(cell);

    // walk the open view's best route, re-planning whenever a cell teaches something
    OpenSides sides(knowledge.OpenView());
    StateFloodFill fill;
    fill.Compute(sides, targets);
    while (fill.Cost(cell, static_cast<Heading>(heading)) > 0) {
      if (fill.Cost(cell, static_cast<Heading>(heading)) == StateFloodFill::kUnreachable) {
        out.goal_unreachable = true;
        break;
      }
      // take the plan's turns and its first move; the next cell may change the plan
      const MazePath plan = fill.PathFrom(sides, cell, static_cast<Heading>(heading));
      const Cell next = plan.cells[1];
      const int dx = next.x - cell.x, dy = next.y - cell.y;
      const int move = dx == 1 ? 0 : dx == -1 ? 2 : dy == 1 ? 1 : 3;
      const int d = (move - heading) & 3;
      record.turns += d == 3 ? 1 : d;
      record.forward_moves += 1;
      heading = move;
      cell = next;
      record.route.push_back(cell);
      if (knowledge.Sense(truth, cell)) {
        sides = OpenSides(knowledge.OpenView());
        fill.Compute(sides, targets);
      }
    }

    record.cells_visited = knowledge.VisitedCount();
    record.time_s = record.forward_moves * options.cell_time_s + record.turns * options.turn_time_s;
    record.open_cost = BestCost(knowledge.OpenView(), truth, &record.open_path);
    record.closed_cost = BestCost(knowledge.ClosedView(), truth, &record.closed_path);
    out.trips.push_back(record);
    out.knowledge.push_back(knowledge);
    if (out.goal_unreachable) break;
    if (record.open_cost >= 0 && record.open_cost == record.closed_cost) {
      out.optimal_found = true;
      break;
    }
  }
  if (!out.trips.empty()) out.best = out.trips.back().closed_path;
  for (int y = 0; y < truth.height(); ++y) {
    for (int x = 0; x < truth.width(); ++x)
      out.visited.push_back(knowledge.Visited({x, y}) ? 1 : 0);
  }
  return out;
}

}  // namespace unimouse
