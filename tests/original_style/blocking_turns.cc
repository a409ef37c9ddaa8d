// SPDX-License-Identifier: GPL-3.0-or-later
// Blocking turns, in the style of the original's micromouse sketch with scripted moves (as its
// dummy solver gave them): drive so many cells keeping centred between the walls, stop, turn in
// place by a quarter turn with one command to each motor and wait on the encoders until the turn
// is done, stop, and so on. The script drives tests/original_style/turns_maze.txt from its start
// to its goal: two cells north, right, two cells east, left, one cell north.
#include <cmath>

#include "sim_robot.h"

SimRobot sr;

const float kMetresPerCount =
    2 * 3.14159265f * SimRobot::WHEEL_RADIUS / (SimRobot::GEAR_RATIO * SimRobot::ENCODER_PPR);
const float kCell = 0.18f;            // m
const float kWallHalfThick = 0.006f;  // m
const int kForward = 250;             // motor command driving straight
const int kTurning = 122;             // motor command turning in place
const float kStopShort = 0.023f;      // m before the goal: the robot coasts the rest
const float kQuarterTurn = 3.14159265f / 2;
const float kTurnEarly = 3.14159265f / 14;  // rad before the quarter turn: it coasts the rest
const unsigned long kSettleMs = 200;
// wall centring on the 45 degree sensors: a wall is one nearer than kSideWall; centred in a
// cell, each reads the distance from its corner to the wall along its 45 degree line
const float kSideWall = 0.1f;
const float kCentred =
    (kCell / 2 - kWallHalfThick - SimRobot::WHEEL_TO_WHEEL / 2) * std::sqrt(2.0f);
const float kCentring = 1300;  // per metre of error

// the moves: F forward that many cells, R and L quarter turns
struct Move {
  char kind;
  int cells;
};
const Move kScript[] = {{'F', 2}, {'R', 0}, {'F', 2}, {'L', 0}, {'F', 1}};
const int kMoves = sizeof(kScript) / sizeof(kScript[0]);
int next = 0;

void stop() {
  sr.leftMotor(0);
  sr.rightMotor(0);
  sr.delay(kSettleMs);
}

void forward(float metres) {
  // what the encoders counted while settling is not part of this move
  sr.leftEncoder();
  sr.rightEncoder();
  long left = 0;
  long right = 0;
  for (;;) {
    sr.update();
    left += sr.leftEncoder();
    right += sr.rightEncoder();
    if (static_cast<float>(left + right) / 2 * kMetresPerCount >= metres - kStopShort) break;
    const float l = sr.leftDistance();
    const float r = sr.rightDistance();
    float error = 0;  // positive: too far right, steer left
    if (l < kSideWall && r < kSideWall) {
      error = l - r;
    } else if (l < kSideWall) {
      error = l - kCentred;
    } else if (r < kSideWall) {
      error = kCentred - r;
    }
    const int steer = static_cast<int>(kCentring * error);
    sr.leftMotor(kForward - steer);
    sr.rightMotor(kForward + steer);
  }
  stop();
}

// +1 a quarter turn left (counter-clockwise), -1 right
void turn(int direction) {
  sr.leftEncoder();
  sr.rightEncoder();
  long left = 0;
  long right = 0;
  // one command to each motor; the rest is waiting
  sr.leftMotor(-direction * kTurning);
  sr.rightMotor(direction * kTurning);
  while (std::fabs(static_cast<float>(right - left) * kMetresPerCount / SimRobot::WHEEL_TO_WHEEL) <
         kQuarterTurn - kTurnEarly) {
    sr.update();
    left += sr.leftEncoder();
    right += sr.rightEncoder();
  }
  stop();
}

void setup() {
  Serial.begin(115200);
  sr.initialize();
  sr.log("blocking turns: ready");
}

void loop() {
  if (next == kMoves) {
    sr.update();
    return;
  }
  const Move& m = kScript[next++];
  if (m.kind == 'F') {
    forward(static_cast<float>(m.cells) * kCell);
  } else {
    turn(m.kind == 'L' ? 1 : -1);
  }
  if (next == kMoves) sr.log("done");
}
