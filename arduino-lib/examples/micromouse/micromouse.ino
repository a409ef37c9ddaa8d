// SPDX-License-Identifier: MIT
// The micromouse contest (dissertation section 5.1.4): explore the maze by Adachi method 0, then
// do a speed run along the best path found, one cell or one quarter turn at a time.
//  - Moving one cell (algorithm 6): both motors forward, the pose estimated from the encoders
//    (eq. 3.29-3.31); the heading is held on the estimate and, between two side walls, centred on
//    them; the move ends at the next cell's centre, or near enough a wall ahead. A wall ahead,
//    while the front sensor still sees it, corrects the estimated distance to the centre, and
//    the motors stop as far short of the centre as the robot rolls on: a quarter turn needs the
//    robot within 7 mm of the centre, or its corners scrape the walls and the wheels slip. At
//    rest the estimate is put back in the middle of the corridor, facing straight along it.
//  - Turning (algorithm 5): the motors opposite until the estimated heading has turned 90 degrees;
//    stopped, if it is more than 2 degrees off, the rest is turned again (up to 3 times).
//  - Walls: while crossing into a cell, the 45-degree sensors see its side walls and the front
//    sensor the wall beyond it (the sensor is blind nearer than 3 cm).
// It logs the speed run's path cost and "done"; `--set end_on_log=done` ends the contest there.
//
// The maze: the simulator tells its size, cell and goal (maze info frame, docs/protocol.md), so
// one image runs classic (180 mm cells) and half-size (90 mm) mazes; without an answer in 1 s it
// takes the classic 16 x 16 maze with the centre goal. Every distance below is for the classic
// maze and robots/unimouse.yaml; in a half-size maze they scale with the cell, and the robot is
// robots/unimouse-half.yaml, the classic one at half scale. The largest maze the firmware holds is
// UNIMOUSE_MAZE_MAX_SIDE a side: 32 on the PC; 16 on a board, where a 32 x 32 flood fill (16 KiB)
// does not fit the 8 KiB of a Mega 2560's RAM.
#include <UnimouseSim.h>
#include <stdio.h>

#ifndef UNIMOUSE_MAZE_MAX_SIDE
#ifdef UNIMOUSE_PC_CORE
#define UNIMOUSE_MAZE_MAX_SIDE 32
#else
#define UNIMOUSE_MAZE_MAX_SIDE 16
#endif
#endif
const uint8_t kMaxSide = UNIMOUSE_MAZE_MAX_SIDE;

SimulationRobot robot(Serial);
RobotConstructionSpecification spec;
PoseEstimator pose(spec);
Maze<kMaxSide, kMaxSide> maze;
FFSolver<kMaxSide, kMaxSide> solver(maze);
PathManager<kMaxSide, kMaxSide> paths(solver, 0, 0, Direction::North, 7, 7, 8, 8);

// the classic maze's distances, scaled to the maze's cell by setupMaze()
float kCell = 0.18f;        // m
float kSideWall = 0.10f;    // m, a 45-degree reading below this is a side wall
float kFrontWall = 0.15f;   // m, a front reading below this, half a cell before the centre
float kFrontStop = 0.035f;  // m, stop here before a wall (the sensor is blind below 0.03)
float kCentred = 0.0509f;   // m, a 45-degree reading when centred between walls
float kSideNear = 0.07f;    // m, a 45-degree reading below this is this cell's side wall
// m, the front reading at the centre with a wall ahead: the wall's face is 84 mm ahead, the
// sensor 60 mm; blind there, but further back a reading tells how far the centre is
float kFrontAtCentre = 0.024f;
// m, how far the robot rolls on after the motors stop from the slow speed: stopping this much
// short of the centre leaves it there, where a quarter turn needs it; the corners sweep 77 mm
// from the axle's middle, the walls stand 84 mm away, so 7 mm past the centre a turn scrapes
float kCoast = 0.009f;
float kScale = 1;                    // the cell over the classic cell
const bool kTraceDecisions = false;  // log "at x y heading do action" for every decision
const int kForward = 300, kSlow = 150, kTurn = 130;

enum class Mode : uint8_t { AwaitMaze, Decide, Forward, Turn, Settle, Done };
Mode mode = Mode::AwaitMaze;
uint8_t x = 0, y = 0;
Direction heading = Direction::North;
Action action = Action::None;
float targetX = 0, targetY = 0, startToGo = 0, targetTheta = 0, minLeft = 9, minRight = 9,
      minFront = 9;
uint32_t settleUntil = 0;
uint8_t turnRetries = 0;  // corrections of the quarter turn under way
uint16_t speedRuns = 0;

float headingAngle(Direction d) { return (1 - static_cast<int>(d)) * PI / 2; }  // north: pi/2

float angleDiff(float a, float b) {
  float d = a - b;
  while (d > PI) d -= 2 * PI;
  while (d <= -PI) d += 2 * PI;
  return d;
}

void drive(int left, int right) {
  robot.motorLeft(left);
  robot.motorRight(right);
}

// at rest in a cell: sideways in its middle and facing `heading` exactly, as the walls keep
// the robot; along the heading the estimate stays, so that a move's overshoot is made good
void snap() {
  Pose p = pose.getPose();
  if (heading == Direction::North || heading == Direction::South) {
    p.x = (x + 0.5f) * kCell;
  } else {
    p.y = (y + 0.5f) * kCell;
  }
  p.theta = headingAngle(heading);
  pose.setPose(p, robot.leftEncoderTotal(), robot.rightEncoderTotal());
}

void settle() {
  drive(0, 0);
  settleUntil = millis() + 80;
  mode = Mode::Settle;
}

void sendWalls() {
  uint8_t frame[4] = {x, y, static_cast<uint8_t>(maze.cell(x, y) & 0x0F),
                      static_cast<uint8_t>(maze.cell(x, y) >> 4)};
  robot.debug(UNIMOUSE_ID_DEBUG_WALLS, frame, 4);
}

// the cell the mouse believes it has reached: the simulator warns when it is not the cell the
// robot is in (the moment a mouse gets lost)
void sendVisited() {
  uint8_t frame[2] = {x, y};
  robot.debug(UNIMOUSE_ID_DEBUG_VISITED, frame, 2);
}

// where the mouse believes it is, for the HUD and the replay to set beside where it is
void sendEstimate() {
  const Pose& p = pose.getPose();
  robot.debugValue("est_x_m", p.x);
  robot.debugValue("est_y_m", p.y);
  robot.debugValue("est_theta_rad", p.theta);
}

void recordWall(Direction side, bool wall) {
  if (wall) {
    maze.placeWall(x, y, side);
  } else {
    maze.removeWall(x, y, side);
  }
}

// the maze as the simulator said (or the classic one), the start cell, and the pose in it
void setupMaze() {
  const MazeInfoSensor& info = robot.maze();
  if (info.received() && info.width() > 0) {
    const uint8_t width = info.width() < kMaxSide ? info.width() : kMaxSide;
    const uint8_t height = info.height() < kMaxSide ? info.height() : kMaxSide;
    if (width != info.width() || height != info.height()) {
      robot.log("the maze is larger than this firmware's room: it explores what fits");
    }
    maze.resize(width, height);
    paths.setGoal(info.goalX0(), info.goalY0(), info.goalX1(), info.goalY1());
    kScale = info.cellMetres() / kCell;
    kCell = info.cellMetres();
  } else {
    maze.resize(16, 16);
    robot.log("no maze from the simulator: a classic 16 x 16 maze, centre goal");
  }
  robot.reportMazeSize(maze.width(), maze.height());
  kSideWall *= kScale;
  kFrontWall *= kScale;
  kFrontStop *= kScale;
  kCentred *= kScale;
  kSideNear *= kScale;
  kFrontAtCentre *= kScale;
  kCoast *= kScale;
  // the robot at the same scale: wheels and track
  spec.leftWheelRadius *= kScale;
  spec.rightWheelRadius *= kScale;
  spec.wheelBaseDistance *= kScale;
  pose = PoseEstimator(spec);
  // the classic start cell: open to the north only
  maze.placeWall(0, 0, Direction::East);
  maze.removeWall(0, 0, Direction::North);
  Pose start;
  start.x = start.y = kCell / 2;
  start.theta = headingAngle(heading);
  pose.setPose(start);
}

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.requestMaze();  // before begin(): in lock-step the answer comes with the first step
  robot.begin();
}

void loop() {
  robot.update();
  if (mode == Mode::AwaitMaze) {
    // in lock-step the answer comes with the first step's frames
    if (!robot.maze().received() && millis() < 1000) return;
    setupMaze();
    mode = Mode::Decide;
  }
  pose.updatePose(robot.leftEncoderTotal(), robot.rightEncoderTotal());
  const Pose& p = pose.getPose();
  switch (mode) {
    case Mode::Decide: {
      const PathManager<kMaxSide, kMaxSide>::Phase before = paths.phase();
      const uint16_t trips = paths.trips();
      action = paths.nextAction(x, y, heading);
      if (kTraceDecisions) {
        char dbg[40];
        snprintf(dbg, sizeof(dbg), "at %u %u %u do %u", x, y, static_cast<unsigned>(heading),
                 static_cast<unsigned>(action));
        robot.log(dbg);
      }
      if (paths.trips() != trips && before == PathManager<kMaxSide, kMaxSide>::Phase::SpeedRun &&
          !paths.towardsGoal()) {
        // a speed run reached the goal
        char line[40];
        snprintf(line, sizeof(line), "speed run %u: path cost %u", ++speedRuns, paths.closedCost());
        robot.log(line);
        robot.log("done");
        mode = Mode::Done;
        drive(0, 0);
        return;
      }
      if (action == Action::None) {
        robot.log("no way to the goal");
        mode = Mode::Done;
        drive(0, 0);
      } else if (action == Action::Forward) {
        // the next cell's centre
        targetX = (x + stepX(heading) + 0.5f) * kCell;
        targetY = (y + stepY(heading) + 0.5f) * kCell;
        startToGo = (targetX - p.x) * stepX(heading) + (targetY - p.y) * stepY(heading);
        minLeft = minRight = minFront = 9;
        mode = Mode::Forward;
      } else {
        targetTheta =
            headingAngle(action == Action::TurnLeft ? turnLeft(heading) : turnRight(heading));
        mode = Mode::Turn;
      }
      break;
    }
    case Mode::Forward: {
      // along the heading, to the next cell's centre
      const float toGo = (targetX - p.x) * stepX(heading) + (targetY - p.y) * stepY(heading);
      const float travelled = startToGo - toGo;
      // the side walls of the cell ahead pass the 45-degree sensors about half a cell before it
      if (toGo < 0.11f * kScale && toGo > 0.07f * kScale) {
        minLeft = fminf(minLeft, robot.leftDistance());
        minRight = fminf(minRight, robot.rightDistance());
      }
      // the wall ahead of the cell, seen before the sensor gets too near to see it
      if (toGo < 0.09f * kScale && toGo > 0.04f * kScale)
        minFront = fminf(minFront, robot.frontDistance());
      const bool wallAhead = minFront < kFrontWall;
      // a wall ahead measures the distance to the centre better than the wheels, which slip
      // and overshoot: each new front reading that agrees with the estimate (within 3 cm)
      // puts the estimate where the wall says
      if (robot.frontSensor().hasNewData()) {
        const float f = robot.frontDistance();
        const float wallToGo = f - kFrontAtCentre;
        if (f > kFrontStop && f < 0.1f * kScale && fabsf(wallToGo - toGo) < 0.03f * kScale) {
          Pose q = p;
          q.x -= (wallToGo - toGo) * stepX(heading);
          q.y -= (wallToGo - toGo) * stepY(heading);
          pose.setPose(q, robot.leftEncoderTotal(), robot.rightEncoderTotal());
          break;  // the next loop goes on from the corrected estimate
        }
      }
      if (toGo <= kCoast || (robot.frontDistance() <= kFrontStop)) {
        x = static_cast<uint8_t>(x + stepX(heading));
        y = static_cast<uint8_t>(y + stepY(heading));
        recordWall(turnLeft(heading), minLeft < kSideWall);
        recordWall(turnRight(heading), minRight < kSideWall);
        recordWall(heading, wallAhead);
        sendWalls();
        sendVisited();
        sendEstimate();
        settle();
        break;
      }
      float correction = 300 * angleDiff(headingAngle(heading), p.theta);
      // only this cell's own side walls centre the robot: where one is missing, the 45-degree
      // sensor sees through the gap a post or a wall beyond at 6-10 cm, and steering on that
      // turns the robot off its heading; in the last 1.5 cm the sensors reach the next posts
      const bool centring = toGo > 0.015f * kScale;
      const float left = robot.leftDistance(), right = robot.rightDistance();
      const bool leftWall = centring && left < kSideNear, rightWall = centring && right < kSideNear;
      // positive turns left: nearer the left wall, the left sensor reads less, so turn right
      if (leftWall && rightWall) {
        correction += 800 / kScale * (left - right);
      } else if (leftWall) {
        correction += 800 / kScale * (left - kCentred);
      } else if (rightWall) {
        correction += 800 / kScale * (kCentred - right);
      }
      if (correction > 120) correction = 120;
      if (correction < -120) correction = -120;
      // ramp up over the first 3 cm, so that the wheels do not spin and fool the encoders
      int base = toGo < 0.03f * kScale ? kSlow : kForward;
      if (travelled < 0.03f * kScale) {
        base = kSlow + static_cast<int>((kForward - kSlow) * travelled / (0.03f * kScale));
      }
      drive(base - static_cast<int>(correction), base + static_cast<int>(correction));
      break;
    }
    case Mode::Turn: {
      const float left = angleDiff(targetTheta, p.theta);
      if (fabsf(left) < (turnRetries == 0 ? 0.06f : 0.01f)) {
        settle();
      } else {
        const int c = fabsf(left) < 0.3f ? kTurn / 2 : kTurn;
        drive(left > 0 ? -c : c, left > 0 ? c : -c);
      }
      break;
    }
    case Mode::Settle:
      if (static_cast<int32_t>(millis() - settleUntil) >= 0) {
        if (action == Action::TurnLeft || action == Action::TurnRight) {
          // a light robot stops short of the turn where a heavy one coasts through it: what the
          // wheels say is missing is turned again, before the heading is taken as exact
          if (fabsf(angleDiff(targetTheta, p.theta)) > 0.035f && turnRetries < 3) {
            ++turnRetries;
            mode = Mode::Turn;
            break;
          }
          heading = action == Action::TurnLeft ? turnLeft(heading) : turnRight(heading);
          turnRetries = 0;
        }
        snap();
        mode = Mode::Decide;
      }
      break;
    case Mode::AwaitMaze:  // left above
    case Mode::Done:
      break;
  }
}
