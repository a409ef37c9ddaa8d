// SPDX-License-Identifier: GPL-3.0-or-later
#include "maze_generator.h"

#include <algorithm>
#include <string>
#include <vector>

#include "rng.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

struct Edge {
  Cell cell;
  Heading side;
};

Cell Beyond(Cell c, int h) { return {c.x + (h == 0) - (h == 2), c.y + (h == 1) - (h == 3)}; }

}  // namespace

Maze GenerateMaze(const GenerateOptions& o) {
  UNIMOUSE_THROW_UNLESS(o.width >= 3 && o.height >= 3 && o.width <= 255 && o.height <= 255,
                        "a generated maze is 3 x 3 to 255 x 255 cells");
  UNIMOUSE_THROW_UNLESS(o.loops >= 0 && o.loops <= 1, "loops must be within [0, 1]");
  RngStream rng(o.seed, "maze.generate");
  auto below = [&](size_t n) {
    return static_cast<size_t>(rng.Uniform() * static_cast<double>(n));
  };

  Maze maze(o.width, o.height);
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      for (int h = 0; h < 4; ++h) maze.SetWall({x, y}, static_cast<Heading>(h), true);
    }
  }
  const std::vector<Cell> goals = CentreCells(o.width, o.height);
  auto is_goal = [&](Cell c) { return std::find(goals.begin(), goals.end(), c) != goals.end(); };
  // walls that stay: the start's east wall, and the goal area's boundary but for one entrance
  auto fixed = [&](Cell c, int h) {
    const Cell n = Beyond(c, h);
    if ((c == Cell{0, 0} && h == 0) || (n == Cell{0, 0} && h == 2)) return true;
    return is_goal(c) != is_goal(n);
  };
  for (Cell g : goals) {
    for (int h = 0; h < 4; ++h) {
      if (is_goal(Beyond(g, h))) maze.SetWall(g, static_cast<Heading>(h), false);
    }
  }

  // a depth-first walk over the cells outside the goal area carves a spanning tree
  std::vector<char> seen(static_cast<size_t>(o.width * o.height), 0);
  auto index = [&](Cell c) { return static_cast<size_t>(c.y * o.width + c.x); };
  std::vector<Cell> stack = {{0, 0}};
  seen[0] = 1;
  while (!stack.empty()) {
    const Cell c = stack.back();
    int options[4], n = 0;
    for (int h = 0; h < 4; ++h) {
      const Cell next = Beyond(c, h);
      if (maze.Contains(next) && !is_goal(next) && !seen[index(next)] && !fixed(c, h)) {
        options[n++] = h;
      }
    }
    if (n == 0) {
      stack.pop_back();
      continue;
    }
    const int h = options[below(static_cast<size_t>(n))];
    maze.SetWall(c, static_cast<Heading>(h), false);
    seen[index(Beyond(c, h))] = 1;
    stack.push_back(Beyond(c, h));
  }

  // one entrance into the goal area
  std::vector<Edge> entrances;
  for (Cell g : goals) {
    for (int h = 0; h < 4; ++h) {
      const Cell n = Beyond(g, h);
      if (maze.Contains(n) && !is_goal(n)) entrances.push_back({g, static_cast<Heading>(h)});
    }
  }
  const Edge door = entrances[below(entrances.size())];
  maze.SetWall(door.cell, door.side, false);

  // loops: open a share of the remaining inner walls, in a random order
  std::vector<Edge> inner;
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      for (int h : {0, 1}) {
        const Cell n = Beyond({x, y}, h);
        if (maze.Contains(n) && maze.HasWall({x, y}, static_cast<Heading>(h)) &&
            !fixed({x, y}, h)) {
          inner.push_back({{x, y}, static_cast<Heading>(h)});
        }
      }
    }
  }
  const size_t opened = static_cast<size_t>(o.loops * static_cast<double>(inner.size()) + 0.5);
  for (size_t i = 0; i < opened; ++i) {
    std::swap(inner[i], inner[i + below(inner.size() - i)]);
    maze.SetWall(inner[i].cell, inner[i].side, false);
  }
  maze.set_start({0, 0}, Heading::kNorth);
  maze.set_goals(goals);
  return maze;
}

}  // namespace unimouse
