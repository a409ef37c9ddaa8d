// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze_solver.h"

#include <cstdint>

#include "unimouse/errors.h"

namespace unimouse {
namespace {

// headings count counter-clockwise from east: turning left adds one
int Left(int h) { return (h + 1) & 3; }
int Right(int h) { return (h + 3) & 3; }
int Back(int h) { return (h + 2) & 3; }

// quarter turns between two headings: 0, 1 or 2
int QuarterTurns(int from, int to) {
  const int d = (to - from) & 3;
  return d == 3 ? 1 : d;
}

constexpr int kNorth = static_cast<int>(Heading::kNorth);
constexpr int kEast = static_cast<int>(Heading::kEast);
constexpr int kSouth = static_cast<int>(Heading::kSouth);
constexpr int kWest = static_cast<int>(Heading::kWest);

}  // namespace

MazePath DescribeRoute(const std::vector<Cell>& cells, Heading start) {
  MazePath path;
  path.found = !cells.empty();
  path.cells = cells;
  int heading = static_cast<int>(start);
  for (size_t i = 1; i < cells.size(); ++i) {
    // 64-bit: a route reported by a firmware may hold any two cells one after the other
    const int64_t dx = int64_t{cells[i].x} - cells[i - 1].x;
    const int64_t dy = int64_t{cells[i].y} - cells[i - 1].y;
    const int move = dx == 1 ? kEast : dx == -1 ? kWest : dy == 1 ? kNorth : kSouth;
    path.turns += QuarterTurns(heading, move);
    path.straights += 1;
    heading = move;
  }
  return path;
}

TieRule TieRule::Parse(const std::string& text) {
  const std::string forms =
      "; a tie rule is compass:<order of N E S W>, relative:<order of F L R B> or "
      "straight:<order of N E S W>, e.g. compass:WENS";
  const size_t colon = text.find(':');
  UNIMOUSE_THROW_UNLESS(colon != std::string::npos, "unknown tie rule '" + text + "'" + forms);
  const std::string kind = text.substr(0, colon), order = text.substr(colon + 1);
  TieRule rule;
  std::string letters;
  if (kind == "compass" || kind == "straight") {
    rule.kind = kind == "compass" ? Kind::kCompass : Kind::kStraightThenCompass;
    letters = "ENWS";  // index = heading
  } else if (kind == "relative") {
    rule.kind = Kind::kRelative;
    letters = "FLBR";  // index = quarter turns to the left
  } else {
    throw InputError("unknown tie rule '" + text + "'" + forms);
  }
  std::string seen;
  UNIMOUSE_THROW_UNLESS(order.size() == 4, "tie rule '" + text + "' needs 4 letters" + forms);
  for (int i = 0; i < 4; ++i) {
    const size_t at = letters.find(order[i]);
    UNIMOUSE_THROW_UNLESS(at != std::string::npos && seen.find(order[i]) == std::string::npos,
                          "tie rule '" + text + "' must use each of " + letters + " once" + forms);
    seen += order[i];
    rule.order[i] = static_cast<int>(at);
  }
  return rule;
}

std::string TieRule::Name() const {
  const std::string letters = kind == Kind::kRelative ? "FLBR" : "ENWS";
  std::string name = kind == Kind::kCompass    ? "compass:"
                     : kind == Kind::kRelative ? "relative:"
                                               : "straight:";
  for (int o : order) name += letters[o];
  return name;
}

OpenSides::OpenSides(const Maze& maze)
    : width_(maze.width()),
      height_(maze.height()),
      step_{1, maze.width(), -1, -maze.width()},
      bits_(static_cast<size_t>(maze.width() * maze.height()), 0) {
  // straight from the edge tables: a side is open if it has no wall and is not the perimeter
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      uint8_t open = 0;
      if (x + 1 < width_ && !maze.HasVerticalWall(x + 1, y)) open |= 1 << kEast;
      if (y + 1 < height_ && !maze.HasHorizontalWall(x, y + 1)) open |= 1 << kNorth;
      if (x > 0 && !maze.HasVerticalWall(x, y)) open |= 1 << kWest;
      if (y > 0 && !maze.HasHorizontalWall(x, y)) open |= 1 << kSouth;
      bits_[static_cast<size_t>(y * width_ + x)] = open;
    }
  }
}

void CellFloodFill::Compute(const OpenSides& sides, const std::vector<Cell>& targets) {
  width_ = sides.width();
  const size_t n = static_cast<size_t>(sides.width() * sides.height());
  distance_.assign(n, kUnreachable);
  queue_.resize(n);
  size_t head = 0, tail = 0;
  for (Cell t : targets) {
    const int i = sides.Index(t);
    if (distance_[i] == kUnreachable) {
      distance_[i] = 0;
      queue_[tail++] = i;
    }
  }
  while (head < tail) {
    const int c = queue_[head++];
    for (int h = 0; h < 4; ++h) {
      if (!sides.Open(c, h)) continue;
      const int next = sides.Neighbour(c, h);
      if (distance_[next] == kUnreachable) {
        distance_[next] = static_cast<uint16_t>(distance_[c] + 1);
        queue_[tail++] = next;
      }
    }
  }
}

MazePath CellFloodFill::PathFrom(const OpenSides& sides, Cell start, Heading heading,
                                 const TieRule& rule) const {
  MazePath path;
  int c = sides.Index(start);
  if (distance_[c] == kUnreachable) return path;
  path.found = true;
  path.cells.push_back(start);
  int h = static_cast<int>(heading);
  while (distance_[c] > 0) {
    auto nearer = [&](int g) {
      return sides.Open(c, g) && distance_[sides.Neighbour(c, g)] == distance_[c] - 1;
    };
    int move = -1;
    if (rule.kind == TieRule::Kind::kStraightThenCompass && nearer(h)) move = h;
    for (int i = 0; move < 0 && i < 4; ++i) {
      const int g = rule.kind == TieRule::Kind::kRelative ? (h + rule.order[i]) & 3 : rule.order[i];
      if (nearer(g)) move = g;
    }
    UNIMOUSE_DEMAND(move >= 0);
    path.turns += QuarterTurns(h, move);
    path.straights += 1;
    h = move;
    c = sides.Neighbour(c, h);
    path.cells.push_back(sides.CellAt(c));
  }
  return path;
}

void StateFloodFill::Compute(const OpenSides& sides, const std::vector<Cell>& targets) {
  width_ = sides.width();
  const size_t n = static_cast<size_t>(4 * sides.width() * sides.height());
  cost_.assign(n, kUnreachable);
  queue_.resize(n);
  size_t head = 0, tail = 0;
  for (Cell t : targets) {
    const int base = 4 * sides.Index(t);
    for (int h = 0; h < 4; ++h) {
      if (cost_[base + h] == kUnreachable) {
        cost_[base + h] = 0;
        queue_[tail++] = base + h;
      }
    }
  }

  // breadth first from the goal states over S2(p), the states that reach p in one action:
  // turning into p's heading from either side, or moving forward into p's cell
  while (head < tail) {
    const int s = queue_[head++];
    const int c = s >> 2, h = s & 3;
    const uint16_t next_cost = static_cast<uint16_t>(cost_[s] + 1);
    const int from_left = 4 * c + Right(h);  // turning left from h-1 faces h
    const int from_right = 4 * c + Left(h);
    if (cost_[from_left] == kUnreachable) {
      cost_[from_left] = next_cost;
      queue_[tail++] = from_left;
    }
    if (cost_[from_right] == kUnreachable) {
      cost_[from_right] = next_cost;
      queue_[tail++] = from_right;
    }
    if (sides.Open(c, Back(h))) {
      const int behind = 4 * sides.Neighbour(c, Back(h)) + h;
      if (cost_[behind] == kUnreachable) {
        cost_[behind] = next_cost;
        queue_[tail++] = behind;
      }
    }
  }
}

MazePath StateFloodFill::PathFrom(const OpenSides& sides, Cell start, Heading heading) const {
  MazePath path;
  int c = sides.Index(start), h = static_cast<int>(heading);
  if (cost_[4 * c + h] == kUnreachable) return path;
  path.found = true;
  path.cells.push_back(start);
  while (cost_[4 * c + h] > 0) {
    const uint16_t want = static_cast<uint16_t>(cost_[4 * c + h] - 1);
    if (sides.Open(c, h) && cost_[4 * sides.Neighbour(c, h) + h] == want) {
      c = sides.Neighbour(c, h);
      path.straights += 1;
      path.cells.push_back(sides.CellAt(c));
    } else if (cost_[4 * c + Left(h)] == want) {
      h = Left(h);
      path.turns += 1;
    } else {
      UNIMOUSE_DEMAND(cost_[4 * c + Right(h)] == want);
      h = Right(h);
      path.turns += 1;
    }
  }
  return path;
}

}  // namespace unimouse
