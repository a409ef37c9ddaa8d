// SPDX-License-Identifier: MIT
// The modified flood fill (dissertation algorithm 2, section 3.4.2): the cost of every robot
// state (cell, heading) to reach a goal cell, where moving one cell forward and turning 90 degrees
// either way each cost 1, so a path's cost counts its turns. Sides not yet seen count as open,
// which is what exploring by flood fill needs. Memory: 4 bytes a state for costs and queue,
// 4 KiB for a 16 x 16 maze; nothing on the heap.
#ifndef UNIMOUSE_SIM_FF_SOLVER_H_
#define UNIMOUSE_SIM_FF_SOLVER_H_

#include <stdint.h>

#include "Maze.h"

/// One step of a path: what the robot does next from a state.
enum class Action : uint8_t { Forward, TurnLeft, TurnRight, None };

template <uint8_t W, uint8_t H>
class FFSolver {
  static_assert(static_cast<uint32_t>(W) * H * 4 < 0xFFFF, "states are counted in 16 bits");

 public:
  static const uint16_t UNREACHABLE = 0xFFFF;

  explicit FFSolver(const Maze<W, H>& maze) : maze_(maze) {}

  /// Costs to the goal area: every cell of the rectangle from (x0, y0) to (x1, y1), inclusive,
  /// reached in any heading. The classic goal is the 2 x 2 centre. Sides not yet seen count as
  /// open, or as walls with `unseenIsWall` (the "closed" maze of Adachi's method).
  void calculateCosts(uint8_t x0, uint8_t y0, uint8_t x1, uint8_t y1, bool unseenIsWall = false) {
    unseenIsWall_ = unseenIsWall;
    for (uint16_t s = 0; s < kStates; ++s) cost_[s] = UNREACHABLE;
    uint16_t head = 0, tail = 0;
    for (uint8_t x = x0; x <= x1; ++x) {
      for (uint8_t y = y0; y <= y1; ++y) {
        for (uint8_t d = 0; d < 4; ++d) {
          const uint16_t s = state(x, y, static_cast<Direction>(d));
          cost_[s] = 0;
          queue_[tail++] = s;
        }
      }
    }
    // breadth first, backwards: the states one action before s are s's cell turned either
    // way, and the cell behind s facing the same way if no wall stands between
    while (head < tail) {
      const uint16_t s = queue_[head++];
      const uint8_t x = cellX(s), y = cellY(s);
      const Direction d = heading(s);
      const uint16_t next = cost_[s] + 1;
      reach(state(x, y, turnLeft(d)), next, &tail);
      reach(state(x, y, turnRight(d)), next, &tail);
      if (!blocked(x, y, turnAround(d))) {
        reach(state(static_cast<uint8_t>(x - stepX(d)), static_cast<uint8_t>(y - stepY(d)), d),
              next, &tail);
      }
    }
  }

  /// The cost from cell (x, y) facing d; UNREACHABLE when no goal can be reached.
  uint16_t cost(uint8_t x, uint8_t y, Direction d) const { return cost_[state(x, y, d)]; }

  /// The action that lowers the cost by one; among equal ones forward, then left, then right.
  /// None at a goal or where the goal cannot be reached.
  Action bestAction(uint8_t x, uint8_t y, Direction d) const {
    const uint16_t here = cost(x, y, d);
    if (here == 0 || here == UNREACHABLE) return Action::None;
    if (!blocked(x, y, d) && cost(static_cast<uint8_t>(x + stepX(d)),
                                  static_cast<uint8_t>(y + stepY(d)), d) == here - 1) {
      return Action::Forward;
    }
    if (cost(x, y, turnLeft(d)) == here - 1) return Action::TurnLeft;
    return Action::TurnRight;
  }

 private:
  static const uint16_t kStates = static_cast<uint16_t>(W) * H * 4;

  static uint16_t state(uint8_t x, uint8_t y, Direction d) {
    return static_cast<uint16_t>((static_cast<uint16_t>(y) * W + x) * 4 + static_cast<uint8_t>(d));
  }
  static uint8_t cellX(uint16_t s) { return static_cast<uint8_t>((s >> 2) % W); }
  static uint8_t cellY(uint16_t s) { return static_cast<uint8_t>((s >> 2) / W); }
  static Direction heading(uint16_t s) { return static_cast<Direction>(s & 3); }

  bool blocked(uint8_t x, uint8_t y, Direction d) const {
    return maze_.hasWall(x, y, d) || (unseenIsWall_ && !maze_.isKnown(x, y, d));
  }

  void reach(uint16_t s, uint16_t c, uint16_t* tail) {
    if (cost_[s] != UNREACHABLE) return;
    cost_[s] = c;
    queue_[(*tail)++] = s;
  }

  const Maze<W, H>& maze_;
  bool unseenIsWall_ = false;
  uint16_t cost_[kStates];
  uint16_t queue_[kStates];  // each state enters once
};

#endif  // UNIMOUSE_SIM_FF_SOLVER_H_
