// SPDX-License-Identifier: MIT
// Adachi method 0 (dissertation section 3.4.3): the robot runs start -> goal -> start -> ...,
// each trip along the modified flood fill's best path over the walls it has seen so far (unseen
// sides open), re-planning whenever it asks for the next action. At the end of every trip it
// compares the best path from the start over the seen walls with unseen sides open and closed:
// when both cost the same, no unexplored route can be shorter, and exploring is over. Then the
// robot goes home if it is not there, and does speed runs along the known best path.
#ifndef UNIMOUSE_SIM_PATH_MANAGER_H_
#define UNIMOUSE_SIM_PATH_MANAGER_H_

#include <stdint.h>

#include "FFSolver.h"
#include "Maze.h"

template <uint8_t W, uint8_t H>
class PathManager {
 public:
  enum class Phase : uint8_t { Exploring, ReturningHome, SpeedRun };

  /// The robot starts in (startX, startY) facing startDir; the goal is the rectangle from
  /// (goalX0, goalY0) to (goalX1, goalY1). The solver plans over the maze the caller records
  /// walls in.
  PathManager(FFSolver<W, H>& solver, uint8_t startX, uint8_t startY, Direction startDir,
              uint8_t goalX0, uint8_t goalY0, uint8_t goalX1, uint8_t goalY1)
      : solver_(solver),
        startX_(startX),
        startY_(startY),
        startDir_(startDir),
        goalX0_(goalX0),
        goalY0_(goalY0),
        goalX1_(goalX1),
        goalY1_(goalY1) {}

  /// What to do next from (x, y) facing d, given the walls recorded so far: Forward, TurnLeft,
  /// TurnRight; None once a trip ends where no next trip can start (the goal is unreachable).
  /// Before a speed run the robot first turns in the start cell to its start heading.
  /// A trip that ends here is counted and the next one planned in the same call.
  Action nextAction(uint8_t x, uint8_t y, Direction d) {
    for (uint8_t attempt = 0; attempt < 2; ++attempt) {
      // a speed run starts from the start state, as the best path's cost counts from there
      if (phase_ == Phase::SpeedRun && towardsGoal_ && x == startX_ && y == startY_ &&
          d != startDir_) {
        return startDir_ == turnRight(d) ? Action::TurnRight : Action::TurnLeft;
      }
      plan();
      const Action a = solver_.bestAction(x, y, d);
      if (a != Action::None) return a;
      if (solver_.cost(x, y, d) == FFSolver<W, H>::UNREACHABLE) return Action::None;
      endTrip();
    }
    return Action::None;
  }

  /// Moves the goal to the rectangle from (x0, y0) to (x1, y1), as the simulator tells it;
  /// before the first trip.
  void setGoal(uint8_t x0, uint8_t y0, uint8_t x1, uint8_t y1) {
    goalX0_ = x0;
    goalY0_ = y0;
    goalX1_ = x1;
    goalY1_ = y1;
  }

  Phase phase() const { return phase_; }
  /// Whether the robot is on its way to the goal (else to the start).
  bool towardsGoal() const { return towardsGoal_; }
  /// Trips ended so far, exploring and speed runs.
  uint16_t trips() const { return trips_; }
  /// The costs from the start, unseen sides open and closed, at the end of the last trip.
  uint16_t openCost() const { return openCost_; }
  uint16_t closedCost() const { return closedCost_; }

 private:
  // costs towards this trip's target: the goal or the start cell; exploring plans over unseen
  // sides open, going home and speed runs only over walls seen to be open
  void plan() {
    const bool closed = phase_ != Phase::Exploring;
    if (towardsGoal_) {
      solver_.calculateCosts(goalX0_, goalY0_, goalX1_, goalY1_, closed);
    } else {
      solver_.calculateCosts(startX_, startY_, startX_, startY_, closed);
    }
  }

  void endTrip() {
    ++trips_;
    if (phase_ == Phase::Exploring) {
      solver_.calculateCosts(goalX0_, goalY0_, goalX1_, goalY1_, true);
      closedCost_ = solver_.cost(startX_, startY_, startDir_);
      solver_.calculateCosts(goalX0_, goalY0_, goalX1_, goalY1_, false);
      openCost_ = solver_.cost(startX_, startY_, startDir_);
      if (openCost_ == closedCost_) phase_ = towardsGoal_ ? Phase::ReturningHome : Phase::SpeedRun;
    } else if (phase_ == Phase::ReturningHome) {
      phase_ = Phase::SpeedRun;
    }
    towardsGoal_ = !towardsGoal_;
  }

  FFSolver<W, H>& solver_;
  uint8_t startX_, startY_;
  Direction startDir_;
  uint8_t goalX0_, goalY0_, goalX1_, goalY1_;
  Phase phase_ = Phase::Exploring;
  bool towardsGoal_ = true;
  uint16_t trips_ = 0;
  uint16_t openCost_ = 0;
  uint16_t closedCost_ = 0;
};

#endif  // UNIMOUSE_SIM_PATH_MANAGER_H_
