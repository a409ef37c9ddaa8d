// SPDX-License-Identifier: MIT
// A fast micromouse: the contest of the micromouse example (explore by Adachi method 0, then a
// speed run), driven as competition mice drive. Read micromouse.ino first; this one adds:
//  - Motion as a queue of segments (straight, curve, pivot, pause) laid out on the maze's exact
//    geometry. A reference pose runs along them on a velocity profile; a tracking controller
//    steers the estimated pose onto the reference (lateral and heading errors turn into angular
//    velocity, the error along the path into speed), and each wheel follows its own reference
//    travel under feedforward (the motor model) and a PD loop on the encoder.
//  - Trapezoidal profiles: accelerate at kAccel, cruise, and brake so as to reach each segment's
//    exit speed exactly at its end (v = sqrt(v_exit^2 + 2 a d) for the distance d left).
//  - Smooth turns: a quarter turn is a curve whose curvature ramps linearly over 20 degrees,
//    holds, and ramps down (a clothoid-arc-clothoid), from one cell edge to the next, at a
//    constant speed whose lateral acceleration v^2 kappa stays under kLateral. Exploring, it
//    has short straights before and after, inside the cell, so that the side sensors look
//    straight ahead before the next decision; in the speed run it fills the cell, except in a
//    staircase of turns, where the explorer's curve leaves a little straight for corrections.
//    Two turns the same way in neighbouring cells, between straights, are one half turn into
//    the next corridor (not on a board).
//  - Exploring never stops except to turn round or to finish: it decides what to do in a cell
//    1.5 cm before entering it, on the walls its sensors saw while approaching. Cells ahead that
//    are known on every side and that the plan crosses straight on, it crosses as one faster
//    straight (kKnown), deciding at the last one's far edge.
//  - Once exploring is over in the goal, the trip home runs over cells seen only, so it is
//    planned and driven as a speed run (planFastPath), to the start cell's centre.
//  - The pose (eq. 3.29-3.31 from the encoders, the heading from the gyro when the robot sends
//    it) is corrected by side walls (the distance from the corridor's centre line, shared
//    between the offset and the heading by a Kalman filter), by a wall ahead and, in the speed
//    run, by the ends of side walls (the distance along it). The tyres slip in proportion to the
//    force they pass, which the estimate takes off the wheels' travel (kSlip, measured on this
//    robot), and in a fast curve sideways, which it adds to the heading's turn (kSideSlip).
//  - When the walls it sees at two decisions in a row are not those its map holds there, it is
//    lost: it says so and ends.
//
// The limits come from robots/unimouse.yaml:
//  - traction: the wheels' friction is 0.35 and they carry 0.147 of the robot's 0.157 kg (the
//    plate is centred on the axle; the caster carries its own 10 g), so the tyres give at most
//    0.35 * 9.81 * 0.147 / 0.157 = 3.2 m/s^2, shared between speeding up and turning; kAccel and
//    kLateral take about half of it each, leaving room for the controller's corrections;
//  - speed: the 30:1 motor (kt 0.079 N m/A at the wheel, 16.7 ohm) turns at 6 V / kt = 76 rad/s
//    without load, 1.21 m/s on the 16 mm wheel; kTop keeps about a sixth of it for control;
//  - feedforward: a wheel's command for a speed is 1023 / 1.21 per m/s (back EMF), and for an
//    acceleration its share of the mass (0.079 kg) times the wheel radius over the torque per
//    command (kt / R * 6 V / 1023): 45 per m/s^2.
// In a half-size maze every length scales with the cell, and so do the speeds (the half-size
// robot has the same motors on wheels of half the radius).
//
// It logs the speed run's path cost and "done"; `--set end_on_log=done` ends the contest there.
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

// On a board the loops take their time. A Mega 2560 does floating point in software (an
// operation some 10 us, a sinf 130 us): one pass takes about 2.2 ms there, so the loops run every
// 3 ms (kLoopMicros, the wheels' speeds still smoothed over 8 ms), take the sines and cosines of
// small angles from their series (sinCos), and the wheels' loop is softer (kWheelP), as the
// commands act 2 to 3 ms after the counts they answer. On the PC a pass takes no simulated time:
// the loops run every millisecond, worked out as written (docs/firmware.md).
#ifdef __AVR__
const bool kBoard = true;
#else
const bool kBoard = false;
#endif
#ifndef RACER_LOOP_MICROS
#define RACER_LOOP_MICROS (kBoard ? 3000 : 1000)
#endif
const uint16_t kLoopMicros = RACER_LOOP_MICROS;
const float kSpeedSmoothing = kLoopMicros == 1000 ? 0.12f : 0.12f * kLoopMicros / 1000;

SimulationRobot robot(Serial);
Maze<kMaxSide, kMaxSide> maze;
FFSolver<kMaxSide, kMaxSide> solver(maze);
PathManager<kMaxSide, kMaxSide> paths(solver, 0, 0, Direction::North, 7, 7, 8, 8);

// the classic maze and robot (scaled by setupMaze() for a half-size maze)
float kScale = 1;
float kCell = 0.18f;             // m
float kWallFace = 0.084f;        // m, from a corridor's centre line to a wall's face
const float kPostHalf = 0.006f;  // m, half a post's side (classic; scaled with the cell)
float kSensorAhead = 0.06f;      // m, the sensors ahead of the axle
float kSensorSide = 0.048f;      // m, the side sensors off the centre line (yawed 45 degrees)
float kWheelBase = 0.096f;       // m
float kWheelRadius = 0.016f;
const float kCountsPerTurn = 358.32f;
float kAccel = 1.6f;            // m/s^2, along the path (traction, above), exploring
float kAccelRun = 1.8f;         // m/s^2, the same in the speed run
float kLateral = 1.8f;          // m/s^2, v^2 kappa in a curve
float kLateralHalfTurn = 1.4f;  // m/s^2, the same in the speed run's half turns
float kTop = 1.0f;              // m/s, on long straights
const float kYawAccel = 35;     // rad/s^2, entering and leaving a curve, exploring
const float kSlip = 0.03f;      // s^2/m, the tyres' slip per m/s^2 (below)
const float kSideSlip = 0.03f;  // s^2/m, the turn the wheels miss per m/s^2 across (below)
const float kSideSlipFrom = 1;  // m/s^2, the lateral acceleration from which they miss it
const float kYawAccelRun = 40;  // rad/s^2, the same in the speed run (curveSpeed)
float kSearch = 0.40f;          // m/s, exploring straights
float kKnown = 0.70f;           // m/s, exploring straights through cells known on every side
float kSideWall = 0.10f;        // m, a 45-degree reading below this is a side wall
float kFrontWall = 0.22f;       // m, a front reading below this while deciding: a wall ahead
float kRange = 1.19f;           // m, a reading nearer than this saw something
float kSenseFrom = 0.06f, kDecideAt = 0.015f;  // m before a cell's edge
float kTurnStraight = 0.03f;                   // m, the straights around an exploring curve
// the quarter-turn curve with curvature 1: the ramps' length (20 degrees each), the whole
// length, and the displacement along and across (equal); a curve of displacement D has a peak
// curvature kTurnShape / D
const float kRampAngle = 0.349066f;
const float kTurnShape = 1.367867f;
const float kTurnLength = 2.268928f;
// the same for the half turn (20-degree ramps, 140 degrees held): its length, its displacement
// across and how far it reaches ahead of where it begins
const float kHalfTurnShape = 2.040439f;
const float kHalfTurnLength = 3.839724f;
const float kHalfTurnReach = 1.347653f;
// How sure the estimate is across the path and of its heading: a Kalman filter's covariance (m^2,
// m rad, rad^2) in the frame of the path. The wheels lose heading as they roll and, more, as they
// turn; a fast curve's side slip more again (at 1.8 m/s^2 across the heading comes out of a
// speed-run curve 2.5 to 4 degrees off, about 3 % of the turn); a turn makes the error along the
// path, a few mm, an error across. A side reading's offset is good to about 3 mm. These numbers
// were chosen over the tests' twenty classic mazes at seeds 2 to 5, and checked at 6 to 8 and 1
// (docs/firmware.md)
const float kHeadingNoise = 1e-4f;       // rad^2 per m rolled
const float kTurnNoise = 2e-4f;          // rad^2 per rad turned, up to 1 m/s^2 across
const float kTurnNoiseFast = 5e-3f;      // rad^2 per rad turned, per m/s^2 across beyond it
const float kAcrossNoise = 1e-6f;        // m^2 per m rolled
const float kAcrossTurnNoise = 1.6e-5f;  // m^2 per rad turned
const float kReadingNoise = 1e-5f;       // m^2, a side reading's offset
float pAA = 1e-6f, pAH = 0, pHH = 1e-4f;
// the filter, not on a board, nor for the half-size robot (below)
bool filtered = true;
// the controllers: wheel travel (command per m and per m/s) and tracking (1/s, 1/m^2)
float kWheelP = kBoard ? 20000 : 30000, kWheelD = 800, kSpeedFF = 845, kAccelFF = 45;
const float kTrackAlong = 6, kTrackSide = 250, kTrackHeading = 14, kTrackHeadingRest = 6;
float trackSide = kTrackSide;  // 1/m^2, scaled with the cell

enum class Kind : uint8_t { Straight, Curve, Pivot, Pause };
struct Segment {
  Kind kind;
  int8_t turn;   // curve and pivot: quarter turns, signed (+ left); a curve of 2: a half turn
  bool sense;    // a straight that ends at the edge of the cell decided on at its end
  float length;  // m; a curve: its displacement across; a pause: s
  float vMax, vExit;
};
#ifdef UNIMOUSE_PC_CORE
const uint8_t kQueue = 128;
#else
const uint8_t kQueue = 64;  // a speed run needs two a turn: planMore queues it as it empties
#endif
Segment queue[kQueue];
uint8_t head = 0, tail = 0;

// the reference: where the robot should be now, and along which segment
float refX, refY, refTheta, refV = 0, refW = 0, refS = 0, endX, endY, endTheta;
// the reference heading's cosine and sine, worked out only when it turns: a Mega 2560 takes
// some 0.1 ms for each, and the loops must fit in the millisecond between encoder frames
float refCos, refSin;
float spin = 0;        // rad/s, a pivot's speed
float refA = 0;        // m/s^2, along a straight
float startX, startY;  // where the segment began
float carried = 0;     // m, how far the reference has run on past the last segment's end
bool segmentStarted = false;
// the estimate
float estX, estY, estTheta;
int32_t lastLeft = 0, lastRight = 0;
float wheelRefL = 0, wheelRefR = 0, wheelL = 0, wheelR = 0, speedL = 0, speedR = 0;
float lastVl = 0, lastVr = 0;
bool hasGyro = false;
float gyroBias = 0;
uint16_t gyroSamples = 0;
uint32_t lastMicros = 0;
float perCount = 0;  // m of a wheel's travel per encoder count

enum class Mode : uint8_t { AwaitMaze, Calibrate, Run, Done };
Mode mode = Mode::AwaitMaze;
uint8_t nextX = 0, nextY = 1;  // the cell the current sensing straight ends at
Direction heading = Direction::North;
float minLeft = 9, minRight = 9, minFront = 9;
bool decided = true;
// what follows when the queue runs out: nothing yet, the speed run, or the end
enum class Then : uint8_t { Explore, Race, Finish };
Then then = Then::Explore;
bool racing = false;
uint16_t speedRunCost = 0;
uint8_t contradicted = 0;   // decisions in a row at which the walls seen contradict the map
bool searching = false;     // lost, and looking for where it is (search)
bool doubtedNoWay = false;  // no way to the goal on the map has begun a search
const bool kTraceDecisions = false;

float headingAngle(Direction d) { return (1 - static_cast<int>(d)) * PI / 2; }  // north: pi/2

float wrap(float a) {
  while (a > PI) a -= 2 * PI;
  while (a <= -PI) a += 2 * PI;
  return a;
}

// the sine and cosine of a; on a board from their series below half a radian (within 2e-6,
// somewhat sooner than sinf and cosf)
void sinCos(float a, float* s, float* c) {
  if (kBoard && fabsf(a) < 0.5f) {
    const float a2 = a * a;
    *s = a * (1 - a2 * (1.0f / 6) * (1 - a2 * (1.0f / 20)));
    *c = 1 - a2 * 0.5f * (1 - a2 * (1.0f / 12) * (1 - a2 * (1.0f / 30)));
    return;
  }
  *s = sinf(a);
  *c = cosf(a);
}

void turnReference(float theta) {
  refTheta = theta;
  refCos = cosf(theta);
  refSin = sinf(theta);
}

// the sine and cosine of a heading; on a board, one near the reference's is the reference's
// turned by the difference
void headingSinCos(float a, float* s, float* c) {
  if (kBoard) {
    const float d = wrap(a - refTheta);
    if (fabsf(d) < 0.5f) {
      float sd, cd;
      sinCos(d, &sd, &cd);
      *s = refSin * cd + refCos * sd;
      *c = refCos * cd - refSin * sd;
      return;
    }
  }
  *s = sinf(a);
  *c = cosf(a);
}

// turns the reference by a step's small angle; at each segment's end it is set exactly
void turnReferenceBy(float dtheta) {
  if (!kBoard) {
    turnReference(wrap(refTheta + dtheta));
    return;
  }
  float s, c;
  headingSinCos(refTheta + dtheta, &s, &c);
  refTheta = wrap(refTheta + dtheta);
  refCos = c;
  refSin = s;
}

void push(Kind kind, float length, float vMax, float vExit, int8_t turn = 0, bool sense = false) {
  if (static_cast<uint8_t>(tail + 1) % kQueue == head) return;  // full: planMore waits for room
  queue[tail] = Segment{kind, turn, sense, length, vMax, vExit};
  tail = static_cast<uint8_t>((tail + 1) % kQueue);
}

bool queueEmpty() { return head == tail; }
uint8_t queueRoom() { return static_cast<uint8_t>(kQueue - 1 - (tail + kQueue - head) % kQueue); }

// the fast path being queued (planFastPath, planMore): whether some is still to queue, and where
// its planning has got to
struct FastPlan {
  bool active, toGoal, first;
  uint8_t x, y;
  Direction d;
  float straight;
};
FastPlan plan = {false, false, false, 0, 0, Direction::North, 0};
void planMore();

// the current curve: its peak curvature, its ramps' length and its whole length
float curvePeak, curveRamp, curveLength;

void startCurve(const Segment& g) {
  const bool half = g.turn == 2 || g.turn == -2;
  curvePeak = (half ? kHalfTurnShape : kTurnShape) / g.length;
  curveRamp = 2 * kRampAngle / curvePeak;
  curveLength = (half ? kHalfTurnLength : kTurnLength) / curvePeak;
}

// the current curve's curvature at s along it (positive: the magnitude)
float curvature(float s) {
  if (s < curveRamp) return curvePeak * s / curveRamp;
  if (s > curveLength - curveRamp) return curvePeak * (curveLength - s) / curveRamp;
  return curvePeak;
}

// the speed at which a curve of peak radius r keeps to kLateral, and its ramps' yaw acceleration
// (v^2 / (2 * ramp angle * r^2)) to kYawAccel: 35 rad/s^2 takes 0.12 N of a wheel's 0.25 N of
// grip, for the robot's 3.3e-4 kg m^2 about the axle's middle (plate, wheels, caster). In the
// speed run 40 rad/s^2 takes 0.14 N, and with the 0.14 N of 1.8 m/s^2 across a wheel needs 0.2 N
// at the ramp's end; the speed run's curve is then held by kLateral alone
float curveSpeed(float r, float yawAccel) {
  return sqrtf(fminf(kLateral, yawAccel * 2 * kRampAngle * r) * r);
}

// the exact pose where the segment at the head of the queue ends
void segmentEnd(const Segment& g) {
  endX = startX;
  endY = startY;
  endTheta = refTheta;
  if (g.kind == Kind::Straight) {
    endX += g.length * refCos;
    endY += g.length * refSin;
  } else if (g.kind == Kind::Curve) {
    const float c = refCos, s = refSin;
    const float along = g.turn == 2 || g.turn == -2 ? 0 : g.length;
    const float across = g.turn > 0 ? g.length : -g.length;
    endX += along * c - across * s;
    endY += along * s + across * c;
    endTheta = wrap(refTheta + g.turn * PI / 2);
  } else if (g.kind == Kind::Pivot) {
    endTheta = wrap(refTheta + g.turn * PI / 2);
  }
}

// advances the reference by dt along the segments; refV and refW are its speeds
void advanceSegments(float dt) {
  refW = 0;
  if (queueEmpty()) {
    refV = 0;
    return;
  }
  Segment& g = queue[head];
  if (!segmentStarted) {
    // the segment begins exactly where the last one ended, and the reference has already run
    // `carried` along it (the last step's overshoot); laid from the reference instead, each
    // segment would shift the rest of the path on by up to a step's travel, and after a few
    // hundred of them the path ran 2 to 4 mm off the corridors' centre lines
    if (g.kind != Kind::Straight && g.kind != Kind::Curve) carried = 0;
    startX = refX - carried * refCos;
    startY = refY - carried * refSin;
    segmentEnd(g);
    if (g.kind == Kind::Curve) startCurve(g);
    segmentStarted = true;
    refS = carried;
    carried = 0;
    spin = 0;
  }
  if (g.kind == Kind::Straight && g.vExit > 0) {
    // along a straight the reference waits for the robot, or catches it up: it goes on from
    // where the estimate is along the line, so that a curve begins where the robot is, not
    // where the reference has got to (the wheels lag it when braking hard); a straight that
    // ends at rest leaves the reference ahead, which then pulls the robot to rest where it is
    const float c = refCos, s = refSin;
    const float along = (estX - startX) * c + (estY - startY) * s;
    if (along > refS - 0.02f * kScale && along < g.length) {
      refS = along;
      refX = startX + along * c;
      refY = startY + along * s;
    }
  }
  bool finished = false;
  float carry = 0;
  if (g.kind == Kind::Straight || g.kind == Kind::Curve) {
    // a curve's length as curveLength, a rounding apart (kept as first written, which the racer's
    // figures in the docs and tests come from)
    const float length = g.kind == Kind::Straight      ? g.length
                         : g.turn == 2 || g.turn == -2 ? kHalfTurnLength * g.length / kHalfTurnShape
                                                       : kTurnLength * g.length / kTurnShape;
    const float left = length - refS;
    const float accel = racing ? kAccelRun : kAccel;
    float v = g.kind == Kind::Curve ? refV : fminf(refV + accel * dt, g.vMax);
    if (g.kind == Kind::Straight) {
      v = fminf(v, sqrtf(g.vExit * g.vExit + 2 * accel * fmaxf(left, 0)));
      // creep the last millimetres to a stop rather than stall short of the end
      if (v < 0.02f * kScale) v = 0.02f * kScale;
    }
    refV = v;
    const float ds = v * dt;
    const float k = g.kind == Kind::Curve ? (g.turn > 0 ? 1 : -1) * curvature(refS + ds / 2) : 0;
    refW = v * k;
    if (k == 0) {
      refX += ds * refCos;
      refY += ds * refSin;
    } else {
      float s, c;
      headingSinCos(refTheta + k * ds / 2, &s, &c);
      refX += ds * c;
      refY += ds * s;
      turnReferenceBy(k * ds);
    }
    refS += ds;
    if (refS >= length) {
      finished = true;
      carry = refS - length;
      if (g.vExit == 0 && g.kind == Kind::Straight) {
        refV = 0;
        carry = 0;
      }
    }
  } else if (g.kind == Kind::Pivot) {
    const float total = fabsf(g.turn) * PI / 2;
    const float alpha = 40, wMax = 10;  // rad/s^2 and rad/s: the wheels at 0.48 m/s, 1.9 m/s^2
    const float left = total - refS;
    float w = fminf(fminf(spin + alpha * dt, wMax), sqrtf(2 * alpha * fmaxf(left, 0)));
    if (w < 0.2f) w = 0.2f;
    spin = w;
    refV = 0;
    refS += w * dt;
    refW = (g.turn > 0 ? 1 : -1) * w;
    turnReferenceBy(refW * dt);
    if (refS >= total) finished = true;
  } else {
    refV = 0;
    refS += dt;
    if (refS >= g.length) finished = true;
  }
  if (finished) {
    refX = endX;
    refY = endY;
    turnReference(endTheta);
    refX += carry * refCos;
    refY += carry * refSin;
    carried = carry;
    head = static_cast<uint8_t>((head + 1) % kQueue);
    segmentStarted = false;
  }
}

// the same, and the reference's acceleration along a straight
void advanceReference(float dt) {
  const float before = refV;
  advanceSegments(dt);
  refA = queueEmpty() || queue[head].kind != Kind::Straight ? 0 : (refV - before) / dt;
  refA = fmaxf(fminf(refA, 3), -3);  // a step of the profile is no acceleration of the robot
}

// the encoders (and the gyro) move the estimate
void updateEstimate(float dt) {
  const int32_t l = robot.leftEncoderTotal(), r = robot.rightEncoderTotal();
  const float dl = (l - lastLeft) * perCount, dr = (r - lastRight) * perCount;
  lastLeft = l;
  lastRight = r;
  wheelL += dl;
  wheelR += dr;
  // the wheels' speeds, smoothed over about 8 ms: one count a millisecond is 0.28 m/s
  speedL += kSpeedSmoothing * (dl / dt - speedL);
  speedR += kSpeedSmoothing * (dr / dt - speedR);
  // the tyres slip in proportion to the force they pass: measured on this robot, the wheels
  // turn 3 % faster than the ground goes by for each m/s^2 of acceleration (and slower when
  // braking), so the travel is the wheels' divided by 1 + 0.03 a
  const float ds = (dl + dr) / 2 / (1 + kSlip * refA);
  float dtheta = hasGyro ? (robot.gyroZ() - gyroBias) * dt : (dr - dl) / kWheelBase;
  // in a fast curve the tyres slip sideways too, and the robot turns more than its wheels say:
  // measured on this robot, 3.5 % more in the speed run's curves (1.8 m/s^2 across), nothing
  // in the explorer's (0.9 m/s^2); the estimate adds 3 % per m/s^2 beyond 1 m/s^2
  const float lateral = fabsf(refV * refW) / kScale - kSideSlipFrom;
  if (!hasGyro && lateral > 0) dtheta *= 1 + kSideSlip * lateral;
  // the covariance follows: the heading's error carries the estimate across as it rolls
  if (!kBoard && filtered) {
    const float ads = fabsf(ds), turn = fabsf(dtheta);
    pAA += ds * (2 * pAH + ds * pHH) + kAcrossNoise * kScale * ads +
           kAcrossTurnNoise * kScale * kScale * turn;
    pAH += ds * pHH;
    pHH += kHeadingNoise / kScale * ads +
           (kTurnNoise + (!hasGyro && lateral > 0 ? kTurnNoiseFast * lateral : 0)) * turn;
  }
  float s, c;
  headingSinCos(estTheta + dtheta / 2, &s, &c);
  estX += ds * c;
  estY += ds * s;
  estTheta = wrap(estTheta + dtheta);
}

// where a side sensor's ray meets a wall's face, along the path (side: +1 left, -1 right), for
// the robot at `along`, `across` off the corridor's centre line, its heading off by e (its sine
// se and cosine ce)
float sideHit(int8_t side, float along, float across, float e, float se, float ce) {
  const float sensorAlong = along + kSensorAhead * ce - side * kSensorSide * se;
  const float sensorAcross = across + kSensorAhead * se + side * kSensorSide * ce;
  const float toWall = side * kWallFace - sensorAcross;
  // the ray is 45 degrees off the heading: on a board, its cotangent from e's sine and cosine
  if (kBoard) return sensorAlong + toWall * (ce - side * se) / (se + side * ce);
  const float ray = e + side * PI / 4;
  return sensorAlong + toWall / sinf(ray) * cosf(ray);
}

// each side sensor's last reading on this straight: whether it was a wall's face, and where
bool sawWall[2] = {false, false};
float lastHit[2];

// a side wall ends at a post's far face, half a post past the cell's edge: when the ray met a
// wall at the last reading and nothing now, the face ended between the two, taken halfway
// (within 1.5 cm at 1 m/s and a reading each 30 ms); returns the shift this gives the distance
// along. Only in the speed run and the trip home driven as one: exploring at 0.4 m/s, the front
// wall and the decisions 1.5 cm before each cell keep it (with it, an exploration of japan9p
// went astray)
float wallEnd(uint8_t i, bool wallNow, float hitNow, float d) {
  float shift = 0;
  if (racing && sawWall[i] && !wallNow && d > 1.5f * kSideWall) {
    const float seen = (lastHit[i] + hitNow) / 2;
    const float post = kPostHalf * kScale;
    const float edge = roundf((seen - post) / kCell) * kCell + post;
    if (fabsf(edge - seen) < 0.03f * kScale) shift = 0.5f * (edge - seen);
  }
  sawWall[i] = wallNow;
  lastHit[i] = hitNow;
  return shift;
}

// a side reading `d` of the offset from the corridor's centre line, `miss` off the estimate's: it
// measures the offset plus the heading's error times a lever (the sensor's distance ahead and the
// ray's across to the wall); the covariance shares it between the two (a Kalman filter's update),
// less the shifts another reading of this pass made. On a board and for the half-size robot the
// shares stay fixed, and only straights turn the heading: with the filter, the main job's contest
// on the board touched walls coming home, and 4 of the 42 half-size mazes lost their speed run
// (neither traced yet)
void sideReading(float miss, float d, float* shiftAcross, float* shiftTheta) {
  if (kBoard || !filtered) {
    *shiftAcross += 0.15f * miss;
    *shiftTheta += 0.3f * miss / (0.1f * kScale);
    return;
  }
  const float lever = kSensorAhead + d * 0.70710678f;
  miss -= *shiftAcross + lever * *shiftTheta;
  const float hA = pAA + lever * pAH, hH = pAH + lever * pHH;
  const float gain = 1 / (hA + lever * hH + kReadingNoise * kScale * kScale);
  const float kA = hA * gain, kH = hH * gain;
  *shiftAcross += kA * miss;
  *shiftTheta += kH * miss;
  pAA -= kA * hA;
  pAH -= kA * hH;
  pHH -= kH * hH;
}

// exploring (not on a board), a wall seen ahead, `seen` along the path, nearer than the end of a
// straight that the plan drives on from: the mouse is not where it believes, or misread. The
// straight ends instead at the edge of the cell walled ahead, where the decision sees that wall;
// if the map holds that side open, that decision begins the search for the mouse's place. On
// the PC, driving on, a kidnapped mouse hit that wall before it noticed, and leaning on it, its
// sensors over the walls, it saw nothing
void wallAhead(float seen, float c, float s) {
  Segment& g = queue[head];
  const float end = startX * c + startY * s + g.length;
  const float edge = seen + (kCell / 2 - kWallFace) - kCell;  // of the cell walled ahead
  const int8_t cut = static_cast<int8_t>(roundf((end - edge) / kCell));
  // too near to end there, sensing that cell's walls on the way: the robot is past that edge
  if (cut < 1 || g.length - cut * kCell < refS + kSenseFrom) return;
  g.length -= cut * kCell;
  segmentEnd(g);
  nextX = static_cast<uint8_t>(nextX - cut * stepX(heading));
  nextY = static_cast<uint8_t>(nextY - cut * stepY(heading));
  contradicted = 1;
}

// the side walls say how far the robot is from the corridor's centre line; a wall ahead, and in
// the speed run the side walls' ends, how far it is along; only on straights, along the maze's
// lines
void correctEstimate() {
  if (queueEmpty()) return;
  const Segment& g = queue[head];
  if (g.kind == Kind::Curve || g.kind == Kind::Pivot) {
    sawWall[0] = sawWall[1] = false;
    return;
  }
  // most passes bring no new reading: nothing to correct
  const bool leftNew = robot.leftSensor().hasNewData();
  const bool rightNew = robot.rightSensor().hasNewData();
  const bool frontNew = robot.frontSensor().hasNewData();
  if (!leftNew && !rightNew && !frontNew) return;
  const float c = refCos, s = refSin;
  const float along = estX * c + estY * s, across = -estX * s + estY * c;  // across: left
  const float centre = (floorf(across / kCell) + 0.5f) * kCell;
  const float e = wrap(estTheta - refTheta);
  float se, ce;
  sinCos(e, &se, &ce);
  float shiftAcross = 0, shiftAlong = 0, shiftTheta = 0;
  const float root = 0.70710678f;
  if (leftNew) {
    const float d = robot.leftDistance();
    const float off =
        kWallFace - d * (root * ce + root * se) - kSensorAhead * se - kSensorSide * ce;
    const bool wall = d < kSideWall && fabsf(off - (across - centre)) < 0.02f * kScale;
    if (wall) sideReading(off - (across - centre), d, &shiftAcross, &shiftTheta);
    shiftAlong += wallEnd(0, wall, sideHit(1, along, across - centre, e, se, ce), d);
  }
  if (rightNew) {
    const float d = robot.rightDistance();
    const float off =
        d * (root * ce - root * se) - kWallFace - kSensorAhead * se + kSensorSide * ce;
    const bool wall = d < kSideWall && fabsf(off - (across - centre)) < 0.02f * kScale;
    if (wall) sideReading(off - (across - centre), d, &shiftAcross, &shiftTheta);
    shiftAlong += wallEnd(1, wall, sideHit(-1, along, across - centre, e, se, ce), d);
  }
  if (frontNew) {
    const float f = robot.frontDistance();
    if (!kBoard && !racing && g.kind == Kind::Straight && g.sense &&
        f < fminf(0.5f * kScale, kRange)) {
      wallAhead(along + (f + kSensorAhead) * ce, c, s);
    }
    if (f > 0.035f * kScale && f < fminf(0.25f * kScale, kRange)) {
      const float seen = along + (f + kSensorAhead) * ce;
      const float face = roundf(seen / kCell) * kCell - (kCell / 2 - kWallFace);
      if (fabsf(seen - face) < 0.04f * kScale) shiftAlong = 0.5f * (face - seen);
    }
  }
  if ((!kBoard && filtered) || g.kind == Kind::Straight) estTheta = wrap(estTheta + shiftTheta);
  estX += shiftAlong * c - shiftAcross * s;
  estY += shiftAlong * s + shiftAcross * c;
}

// the tracking controller and the wheels' loops
void control(float dt) {
  const float c = refCos, s = refSin;
  const float ex = c * (refX - estX) + s * (refY - estY);
  const float ey = -s * (refX - estX) + c * (refY - estY);
  const float eth = wrap(refTheta - estTheta);
  float se, ce;
  sinCos(eth, &se, &ce);
  const float v = refV * ce + kTrackAlong * ex;
  const float w = refW + refV * (trackSide * ey + kTrackHeading * se) + kTrackHeadingRest * se;
  const float vl = v - w * kWheelBase / 2, vr = v + w * kWheelBase / 2;
  const float al = (vl - lastVl) / dt, ar = (vr - lastVr) / dt;
  lastVl = vl;
  lastVr = vr;
  wheelRefL += vl * dt;
  wheelRefR += vr * dt;
  // a wheel that slipped or stalled does not wind its loop up
  const float limit = 0.005f * kScale;
  wheelRefL = fmaxf(fminf(wheelRefL, wheelL + limit), wheelL - limit);
  wheelRefR = fmaxf(fminf(wheelRefR, wheelR + limit), wheelR - limit);
  const float ul = kSpeedFF * vl + kAccelFF * fmaxf(fminf(al, 5), -5) +
                   kWheelP * (wheelRefL - wheelL) + kWheelD * (vl - speedL);
  const float ur = kSpeedFF * vr + kAccelFF * fmaxf(fminf(ar, 5), -5) +
                   kWheelP * (wheelRefR - wheelR) + kWheelD * (vr - speedR);
  robot.motorLeft(static_cast<int32_t>(ul));
  robot.motorRight(static_cast<int32_t>(ur));
}

void sendWalls(uint8_t x, uint8_t y) {
  uint8_t frame[4] = {x, y, static_cast<uint8_t>(maze.cell(x, y) & 0x0F),
                      static_cast<uint8_t>(maze.cell(x, y) >> 4)};
  robot.debug(UNIMOUSE_ID_DEBUG_WALLS, frame, 4);
}

// the cell the mouse is about to enter, and where it believes it is: the simulator warns when
// that cell is not next to the robot's (the moment a mouse gets lost), and its HUD and replay
// set the estimate beside the truth
void sendPosition(uint8_t x, uint8_t y) {
  uint8_t frame[2] = {x, y};
  robot.debug(UNIMOUSE_ID_DEBUG_VISITED, frame, 2);
  robot.debugValue("est_x_m", estX);
  robot.debugValue("est_y_m", estY);
  robot.debugValue("est_theta_rad", estTheta);
}

void recordWall(uint8_t x, uint8_t y, Direction side, bool wall) {
  if (wall) {
    maze.placeWall(x, y, side);
  } else {
    maze.removeWall(x, y, side);
  }
}

Direction turned(Direction d, Action a) {
  return a == Action::TurnLeft ? turnLeft(d) : turnRight(d);
}

void finish(const char* why) {
  if (why) robot.log(why);
  robot.log("done");
  mode = Mode::Done;
}

// the last path planned, for the simulator's pictures: n, then each cell's x and y
// (UNIMOUSE_ID_DEBUG_PATH); room for 128 cells on a board, 255 on the PC
const uint8_t kPathCells = kMaxSide >= 32 ? 255 : kMaxSide * 8;
uint8_t pathFrame[1 + 2 * kPathCells];

void addPathCell(uint8_t x, uint8_t y) {
  if (pathFrame[0] == kPathCells) return;
  pathFrame[1 + 2 * pathFrame[0]] = x;
  pathFrame[2 + 2 * pathFrame[0]] = y;
  ++pathFrame[0];
}

// queues the best path over the walls seen from cell (x, y) facing d, to the goal or home to the
// start cell, as a speed run drives it: straights merged, quarter turns as curves that fill their
// cell. It begins in the cell's centre at rest (the speed run) or at its edge on the way in (the
// trip home once exploring is over, which may first turn round in that cell); it ends on through
// the open cells straight ahead of the goal, or in the start cell's centre facing north. Returns
// the path's cost, UNREACHABLE with nothing queued. Home, the solver already holds the costs:
// PathManager has just planned the way home over the walls seen (a flood fill the less, 21 ms on
// a board, in which the robot drives on without its loops)
uint16_t planFastPath(uint8_t x, uint8_t y, Direction d, bool fromCentre, bool toGoal) {
  if (toGoal) {
    solver.calculateCosts(robot.maze().received() ? robot.maze().goalX0() : 7,
                          robot.maze().received() ? robot.maze().goalY0() : 7,
                          robot.maze().received() ? robot.maze().goalX1() : 8,
                          robot.maze().received() ? robot.maze().goalY1() : 8, true);
  }
  const uint16_t cost = solver.cost(x, y, d);
  if (cost == FFSolver<kMaxSide, kMaxSide>::UNREACHABLE) return cost;
  const Action a0 = solver.bestAction(x, y, d);
  if (!fromCentre && (a0 == Action::TurnLeft || a0 == Action::TurnRight) &&
      solver.bestAction(x, y, turned(d, a0)) != Action::Forward) {
    // the way on is back: stop in the cell's centre and turn round there, as exploring does
    push(Kind::Straight, kCell / 2, kSearch, 0);
    push(Kind::Pivot, 0, 0, 0, static_cast<int8_t>(a0 == Action::TurnLeft ? 2 : -2));
    push(Kind::Pause, 0.05f, 0, 0);
    d = turnAround(d);
    fromCentre = true;
  }
  pathFrame[0] = 0;
  addPathCell(x, y);
  plan = FastPlan{true, toGoal, fromCentre, x, y, d, 0};
  planMore();
  racing = true;
  return cost;
}

// queues more of the fast path planFastPath began, as much as the queue has room for: a path of
// many turns takes more segments than a board's queue holds (apec1998's paths up to 77, torture's
// race some 280, the PC's 128). Cut short, its last segments are slowed as if a staircase's curve
// came next (the slowest way on), until the rest is queued
void planMore() {
  uint8_t x = plan.x, y = plan.y;
  Direction d = plan.d;
  const bool toGoal = plan.toGoal;
  const float d90 = kCell / 2;
  const float vTurn = curveSpeed(d90 / kTurnShape, kYawAccelRun);
  // a half turn from one corridor to the next reaches kHalfTurnReach / kHalfTurnShape of a cell
  // ahead of where it begins; at its far side the robot's wheels (half its width ahead) should
  // keep 2 cm from the wall's face, so it begins that much before the first cell's edge. It
  // turns twice as far as a quarter turn, so it keeps to kLateralHalfTurn
  const float vHalfTurn = sqrtf(kLateralHalfTurn * kCell / kHalfTurnShape);
  const float halfTurnEarly = kCell * kHalfTurnReach / kHalfTurnShape - kCell / 2 + kWheelBase / 2 +
                              kWheelRadius + 0.02f * kScale - kWallFace;
  float straight = plan.straight;
  bool first = plan.first;
  bool cut = false;
  for (;;) {
    if (queueRoom() < 4) {
      // the queue is full: the rest when it has room
      cut = true;
      break;
    }
    const Action a = solver.bestAction(x, y, d);
    if (a == Action::None) break;
    if (a == Action::Forward) {
      straight += first ? kCell / 2 : kCell;
      first = false;
    } else {
      const int8_t side = a == Action::TurnLeft ? 1 : -1;
      const bool turnBefore = straight == 0;
      d = turned(d, a);
      if (solver.bestAction(x, y, d) != Action::Forward) break;  // never on a best path
      const uint8_t x1 = static_cast<uint8_t>(x + stepX(d)),
                    y1 = static_cast<uint8_t>(y + stepY(d));
      const Action after = solver.bestAction(x1, y1, d);
      if (toGoal && !kBoard && straight >= kCell && after == a &&
          solver.bestAction(x1, y1, turned(d, a)) == Action::Forward) {
        const Direction d2 = turned(d, a);
        const Action then2 = solver.bestAction(static_cast<uint8_t>(x1 + stepX(d2)),
                                               static_cast<uint8_t>(y1 + stepY(d2)), d2);
        if (then2 == Action::Forward || then2 == Action::None) {
          // two turns the same way in neighbouring cells, a cell or more of straight before them
          // and a straight after: one half turn, begun early enough that the robot's side stays
          // clear of the wall ahead. After a shorter straight it would run at the speed of the
          // curve before; on the way home it is not used (tried there, the main job's race after
          // it touched a wall), nor on a board (there the main job's race touched posts in one)
          push(Kind::Straight, straight - halfTurnEarly, kTop, vHalfTurn);
          push(Kind::Curve, kCell, vHalfTurn, vHalfTurn, static_cast<int8_t>(2 * side));
          straight = -halfTurnEarly;
          x = x1;
          y = y1;
          addPathCell(x, y);
          d = d2;
          x = static_cast<uint8_t>(x + stepX(d));
          y = static_cast<uint8_t>(y + stepY(d));
          addPathCell(x, y);
          continue;
        }
      }
      if (turnBefore || after == Action::TurnLeft || after == Action::TurnRight) {
        // a staircase of turns has no straight in which to correct a curve's error, so its
        // curves are the explorer's, with their short straights, at its speed
        const float v = curveSpeed((kCell / 2 - kTurnStraight) / kTurnShape, kYawAccel);
        push(Kind::Straight, straight + kTurnStraight, kTop, v);
        push(Kind::Curve, kCell / 2 - kTurnStraight, v, v, side);
        straight = kTurnStraight;
      } else {
        if (straight > 0) push(Kind::Straight, straight, kTop, vTurn);
        push(Kind::Curve, d90, vTurn, vTurn, side);
        straight = 0;
      }
    }
    x = static_cast<uint8_t>(x + stepX(d));
    y = static_cast<uint8_t>(y + stepY(d));
    addPathCell(x, y);
  }
  if (cut) {
    plan = FastPlan{true, toGoal, first, x, y, d, straight};
  } else {
    if (toGoal) {
      // into the goal, then on through the open cells straight ahead (up to two) to a stop
      float room = kCell / 2;
      for (uint8_t i = 0; i < 2 && !maze.hasWall(x, y, d); ++i) {
        if (!maze.isKnown(x, y, d)) break;
        x = static_cast<uint8_t>(x + stepX(d));
        y = static_cast<uint8_t>(y + stepY(d));
        room += kCell;
        addPathCell(x, y);
      }
      push(Kind::Straight, straight + room, kTop, 0);
    } else {
      push(Kind::Straight, straight + kCell / 2, kTop, 0);
    }
  }
  // backwards: a curve runs at the speed it is entered at, so each one is slowed to what the
  // straight after it can brake from for the next
  float next = cut ? curveSpeed((kCell / 2 - kTurnStraight) / kTurnShape, kYawAccel) : 0;
  for (uint8_t i = tail; i != head;) {
    i = static_cast<uint8_t>((i + kQueue - 1) % kQueue);
    Segment& g = queue[i];
    if (g.kind == Kind::Straight) {
      g.vExit = fminf(g.vExit, next);
      next = fminf(g.vMax, sqrtf(g.vExit * g.vExit + 2 * kAccelRun * g.length));
    } else {
      g.vMax = g.vExit = fminf(g.vMax, next);
      next = g.vMax;
    }
  }
  if (cut) return;
  if (!toGoal) {
    const int quarter = (static_cast<int>(d) - static_cast<int>(Direction::North) + 4) % 4;
    if (quarter != 0) push(Kind::Pivot, 0, 0, 0, static_cast<int8_t>(quarter == 3 ? -1 : quarter));
    push(Kind::Pause, 0.3f, 0, 0);  // home: a pause, then the race
  }
  robot.debug(UNIMOUSE_ID_DEBUG_PATH, pathFrame, static_cast<uint16_t>(1 + 2 * pathFrame[0]));
  plan.active = false;
}

// the speed run from the start cell's centre, facing north, along the best path over the walls
// seen
void planSpeedRun() {
  speedRunCost = planFastPath(0, 0, Direction::North, true, true);
  if (speedRunCost == FFSolver<kMaxSide, kMaxSide>::UNREACHABLE) finish("no way to the goal");
}

// Finding its place again once lost (not on a board, where a decision late in a search would stop
// the loops for a few tenths of a second: docs/firmware.md). The mouse goes on in the frame it
// believed in, which is the maze's moved by whole cells and turned by quarter turns, and keeps the
// walls of each cell it sees there. A candidate is such a move: the cell where the search began put
// within kNear cells of where it was believed to be, facing any of four ways. One drops out when a
// cell seen would lie outside the maze under it, or a side seen disagrees with a side the map
// knows. The mouse moves on to cells it has not seen while lost, straight on first, and by the
// walls on its left when all around are seen. When a single candidate is left and at least
// kSureAgree known sides agreed with it, the estimate, the plan and what it saw move there and
// exploring goes on. Candidates in cells not yet explored agree with anything and may never drop
// out: then, after kSearchDecisions, it says so and ends; so it does when none is left, when it
// sees nothing at all (it leans on a wall), and when it is lost a fourth time
const uint8_t kSearchDecisions = 60, kSearches = 3, kSureAgree = 8, kNear = 3;
struct SeenCell {
  int8_t x, y;    // in the frame believed in
  uint8_t walls;  // by direction's bit (sideBit), the way in open
};

// the cells the last kRecent decisions recorded, as seen: what a mouse saw between getting lost
// and noticing went into the map in the wrong cells. They are forgotten when the search begins;
// once the place is found, the newest go back in where they fit the place found, and the older,
// from before it got lost, where they were
const uint8_t kRecent = kBoard ? 1 : 12;
SeenCell recent[kRecent];
uint8_t recentNext = 0, recentCount = 0;

SeenCell seenCell(int8_t x, int8_t y, Direction d, const bool seen[3]) {
  uint8_t walls = 0;
  if (seen[0]) walls |= sideBit(turnLeft(d));
  if (seen[1]) walls |= sideBit(turnRight(d));
  if (seen[2]) walls |= sideBit(d);
  return SeenCell{x, y, walls};
}

void rememberRecorded(const SeenCell& cell) {
  recent[recentNext] = cell;
  recentNext = static_cast<uint8_t>((recentNext + 1) % kRecent);
  if (recentCount < kRecent) ++recentCount;
}

// the cells seen while lost, in the frame believed in
SeenCell seenLost[kBoard ? 1 : kSearchDecisions + 1];
uint8_t seenCount = 0, searchDecisions = 0, searches = 0;
int8_t searchX, searchY;  // the cell about to be entered where the search began

// the cell seen while lost at (x, y) in the frame believed in, if any
int8_t seenAt(int x, int y) {
  for (uint8_t i = 0; i < seenCount; ++i) {
    if (seenLost[i].x == x && seenLost[i].y == y) return static_cast<int8_t>(i);
  }
  return -1;
}

// a candidate: the search's first cell at (cx, cy), the frame turned k quarter turns (left);
// (x, y) in the frame believed in, there
void placeUnder(uint8_t cx, uint8_t cy, uint8_t k, int x, int y, int* px, int* py) {
  const int dx = x - searchX, dy = y - searchY;
  const int c = k == 0 ? 1 : k == 2 ? -1 : 0, s = k == 1 ? 1 : k == 3 ? -1 : 0;
  *px = cx + c * dx - s * dy;
  *py = cy + s * dx + c * dy;
}
Direction turnedBy(Direction d, uint8_t k) {
  return static_cast<Direction>((static_cast<uint8_t>(d) + 4 - k) % 4);
}

// the known sides of a cell seen that agree under a candidate; -1 if it falls outside the maze or
// a side disagrees
int16_t agreeing(const SeenCell& cell, uint8_t cx, uint8_t cy, uint8_t k) {
  int px, py;
  placeUnder(cx, cy, k, cell.x, cell.y, &px, &py);
  if (!maze.contains(px, py)) return -1;
  int16_t known = 0;
  for (uint8_t a = 0; a < 4; ++a) {
    const Direction d = turnedBy(static_cast<Direction>(a), k);
    const uint8_t x = static_cast<uint8_t>(px), y = static_cast<uint8_t>(py);
    if (!maze.isKnown(x, y, d)) continue;
    if (maze.hasWall(x, y, d) != ((cell.walls & sideBit(static_cast<Direction>(a))) != 0)) {
      return -1;
    }
    ++known;
  }
  return known;
}

// the same for every cell seen while lost
int16_t agreeing(uint8_t cx, uint8_t cy, uint8_t k) {
  int16_t known = 0;
  for (uint8_t i = 0; i < seenCount; ++i) {
    const int16_t sides = agreeing(seenLost[i], cx, cy, k);
    if (sides < 0) return -1;
    known = static_cast<int16_t>(known + sides);
  }
  return known;
}

// puts a cell seen into the map, under a candidate
void recordCell(const SeenCell& cell, uint8_t cx, uint8_t cy, uint8_t k) {
  int px, py;
  placeUnder(cx, cy, k, cell.x, cell.y, &px, &py);
  if (!maze.contains(px, py)) return;
  for (uint8_t a = 0; a < 4; ++a) {
    const Direction d = static_cast<Direction>(a);
    recordWall(static_cast<uint8_t>(px), static_cast<uint8_t>(py), turnedBy(d, k),
               (cell.walls & sideBit(d)) != 0);
  }
}

void forgetRecent() {
  for (uint8_t i = 0; i < recentCount; ++i) {
    if (!maze.contains(recent[i].x, recent[i].y)) continue;
    for (uint8_t a = 0; a < 4; ++a) {
      maze.forget(static_cast<uint8_t>(recent[i].x), static_cast<uint8_t>(recent[i].y),
                  static_cast<Direction>(a));
    }
  }
}

// once found under (cx, cy, k): the cells forgotten go back in, the newest under the place found
// while they fit it, the rest where they were believed to be while they fit there
void restoreRecent(uint8_t cx, uint8_t cy, uint8_t k) {
  const uint8_t believedX = static_cast<uint8_t>(searchX),
                believedY = static_cast<uint8_t>(searchY);
  bool found = true;
  for (uint8_t n = 1; n <= recentCount; ++n) {
    const SeenCell& cell = recent[(recentNext + kRecent - n) % kRecent];
    if (found && agreeing(cell, cx, cy, k) < 0) found = false;
    if (found) {
      recordCell(cell, cx, cy, k);
    } else if (agreeing(cell, believedX, believedY, 0) >= 0) {
      recordCell(cell, believedX, believedY, 0);
    }
  }
  recentCount = 0;
}

// the mouse, about to enter (nextX, nextY) facing `heading`, is about to enter (x, y) facing d:
// the estimate, the reference and the segment under way turn and move with it, by k quarter
// turns about the cells' centres
void moveTo(uint8_t x, uint8_t y, Direction d, uint8_t k) {
  const float c = k == 0 ? 1 : k == 2 ? -1 : 0, s = k == 1 ? 1 : k == 3 ? -1 : 0;
  const float fromX = (nextX + 0.5f) * kCell, fromY = (nextY + 0.5f) * kCell;
  const float toX = (x + 0.5f) * kCell, toY = (y + 0.5f) * kCell;
  float* points[][2] = {{&estX, &estY}, {&refX, &refY}, {&startX, &startY}, {&endX, &endY}};
  for (auto& p : points) {
    const float dx = *p[0] - fromX, dy = *p[1] - fromY;
    *p[0] = toX + c * dx - s * dy;
    *p[1] = toY + s * dx + c * dy;
  }
  const float turn = k * PI / 2;
  estTheta = wrap(estTheta + turn);
  endTheta = wrap(endTheta + turn);
  turnReference(wrap(refTheta + turn));
  sawWall[0] = sawWall[1] = false;
  nextX = x;
  nextY = y;
  heading = d;
}

// one decision while lost, about to enter (nextX, nextY) facing `heading` in the frame believed
// in: true when the mouse has found its place (nextX, nextY and heading are then where it is
// about to enter, in the maze), false when it has queued its next move or ended
bool search(const bool seen[3], bool blind, bool begin) {
  // where it believes it is: outside the maze, when that is wrong enough
  const int8_t atX = static_cast<int8_t>(nextX), atY = static_cast<int8_t>(nextY);
  if (begin) {
    if (++searches > kSearches) {
      finish("lost: again, a fourth time");
      return false;
    }
    seenCount = searchDecisions = 0;
    searchX = atX;
    searchY = atY;
    forgetRecent();
  }
  if (blind) {
    finish("lost: it sees no wall at all (stuck on one?)");
    return false;
  }
  if (seenAt(atX, atY) < 0) seenLost[seenCount++] = seenCell(atX, atY, heading, seen);
  // the candidates left, and the known sides that agreed with the last of them
  uint16_t count = 0;
  int16_t agreed = 0;
  uint8_t foundX = 0, foundY = 0, foundK = 0;
  for (int cy = searchY - kNear; cy <= searchY + kNear; ++cy) {
    for (int cx = searchX - kNear; cx <= searchX + kNear; ++cx) {
      if (!maze.contains(cx, cy)) continue;
      for (uint8_t k = 0; k < 4; ++k) {
        const int16_t known = agreeing(static_cast<uint8_t>(cx), static_cast<uint8_t>(cy), k);
        if (known < 0) continue;
        ++count;
        agreed = known;
        foundX = static_cast<uint8_t>(cx);
        foundY = static_cast<uint8_t>(cy);
        foundK = k;
      }
    }
  }
  if (count == 1 && agreed >= kSureAgree) {
    // what it saw goes into the map: before the search where it fits, and while lost where it was
    restoreRecent(foundX, foundY, foundK);
    for (uint8_t i = 0; i < seenCount; ++i) recordCell(seenLost[i], foundX, foundY, foundK);
    int x, y;
    placeUnder(foundX, foundY, foundK, atX, atY, &x, &y);
    moveTo(static_cast<uint8_t>(x), static_cast<uint8_t>(y), turnedBy(heading, foundK), foundK);
    char line[72];
    snprintf(line, sizeof(line), "found: about to enter cell (%d, %d) after %u cells", x, y,
             seenCount);
    robot.log(line);
    return true;
  }
  if (count == 0 || ++searchDecisions > kSearchDecisions) {
    finish(count == 0 ? "lost: the walls seen are nowhere in the map"
                      : "lost: the walls seen fit more than one place in the map");
    return false;
  }
  // on to a cell not seen while lost, straight on first; else by the walls on the left
  const int8_t order[3] = {0, 1, -1};
  int8_t quarters = 2;
  for (int8_t q : order) {
    const bool open = !seen[q == 0 ? 2 : q == 1 ? 0 : 1];
    const Direction d = static_cast<Direction>((static_cast<uint8_t>(heading) + 4 - q) % 4);
    if (open && seenAt(atX + stepX(d), atY + stepY(d)) < 0) {
      quarters = q;
      break;
    }
  }
  if (quarters == 2) quarters = !seen[0] ? 1 : !seen[2] ? 0 : !seen[1] ? -1 : 2;
  // the moves decide() queues, written out again: a change to the code of decide(), which the
  // board runs, re-rolls the board's contests (docs/firmware.md, "On the emulated board")
  if (quarters == 0) {
    push(Kind::Straight, kCell, kSearch, kSearch, 0, true);
  } else if (quarters == 2) {
    push(Kind::Straight, kCell / 2, kSearch, 0);
    push(Kind::Pivot, 0, 0, 0, 2);
    push(Kind::Pause, 0.05f, 0, 0);
    push(Kind::Straight, kCell / 2, kSearch, kSearch, 0, true);
  } else {
    const float vTurn = curveSpeed((kCell / 2 - kTurnStraight) / kTurnShape, kYawAccel);
    push(Kind::Straight, kTurnStraight, kSearch, vTurn);
    push(Kind::Curve, kCell / 2 - kTurnStraight, vTurn, vTurn, quarters);
    push(Kind::Straight, kTurnStraight, kSearch, kSearch, 0, true);
  }
  heading = static_cast<Direction>((static_cast<uint8_t>(heading) + 4 - quarters) % 4);
  nextX = static_cast<uint8_t>(nextX + stepX(heading));
  nextY = static_cast<uint8_t>(nextY + stepY(heading));
  return false;
}

// the robot is about to enter (nextX, nextY) facing `heading`: record its walls and queue what
// it does in it, through to the next cell's edge
void decide() {
  uint8_t x = nextX, y = nextY;
  if (minLeft > 8) minLeft = robot.leftDistance();
  if (minRight > 8) minRight = robot.rightDistance();
  if (minFront > 8) minFront = robot.frontDistance();
  // lost: a side of this cell the map already holds seen otherwise, at two decisions in a row (a
  // single misreading happens: once each in 5 of the 42 half-size contests; twice in a row in
  // none of 152 contests but the one lost, japan2016-ef, 1.1 s after it was). It looks for its
  // place (search); on a board it says so and ends, rather than drive on where it is not
  const bool seen[3] = {minLeft < kSideWall, minRight < kSideWall, minFront < kFrontWall};
  const Direction sides[3] = {turnLeft(heading), turnRight(heading), heading};
  bool contradiction = false;
  // (searching, the cell believed in may lie outside the maze; the search checks the walls)
  for (uint8_t i = 0; i < 3 && (kBoard || !searching); ++i) {
    if (maze.isKnown(x, y, sides[i]) && maze.hasWall(x, y, sides[i]) != seen[i]) {
      contradiction = true;
    }
  }
  contradicted = contradiction ? contradicted + 1 : 0;
  if (!kBoard && (searching || contradicted == 2)) {
    // no reading at all, on every side: the robot leans on a wall, its sensors over the walls
    // (the half-size robot's short-range sensors see nothing in an open cell)
    const bool blind = kScale == 1 && minLeft >= kRange && minRight >= kRange && minFront >= kRange;
    if (!searching) robot.log("lost: the walls seen are not the map's; looking for where they are");
    searching = !search(seen, blind, !searching);
    if (searching) {
      minLeft = minRight = minFront = 9;
      return;
    }
    contradicted = 0;
    x = nextX;
    y = nextY;
  } else if (contradicted == 2) {
    char line[72];
    snprintf(line, sizeof(line), "lost: the walls seen at cell (%u, %u) are not the map's", x, y);
    finish(line);
    return;
  }
  recordWall(x, y, turnLeft(heading), minLeft < kSideWall);
  recordWall(x, y, turnRight(heading), minRight < kSideWall);
  recordWall(x, y, heading, minFront < kFrontWall);
  if (!kBoard) {
    rememberRecorded(seenCell(static_cast<int8_t>(x), static_cast<int8_t>(y), heading, seen));
  }
  sendWalls(x, y);
  sendPosition(x, y);
  minLeft = minRight = minFront = 9;
  Action a = paths.nextAction(x, y, heading);
  if (!kBoard && a == Action::None && !doubtedNoWay) {
    // a contest's maze has a way to the goal: none on the map may mean walls recorded in the
    // wrong cells by a mouse lost in cells it had not seen, where nothing contradicts (so it was
    // in 10 of 12 kidnapped contests that never noticed). Once a contest it looks for its place;
    // where it finds the one it believed, there is indeed no way
    doubtedNoWay = true;
    robot.log("no way to the goal on the map: looking for where it is");
    searching = !search(seen, false, true);
    if (searching) return;
    x = nextX;
    y = nextY;
    a = paths.nextAction(x, y, heading);
  }
  if (kTraceDecisions) {
    char line[40];
    snprintf(line, sizeof(line), "at %u %u %u do %u", x, y, static_cast<unsigned>(heading),
             static_cast<unsigned>(a));
    robot.log(line);
  }
  if (paths.phase() == PathManager<kMaxSide, kMaxSide>::Phase::ReturningHome &&
      planFastPath(x, y, heading, false, false) != FFSolver<kMaxSide, kMaxSide>::UNREACHABLE) {
    // exploring is over: the way home runs over cells seen, so it is driven as a speed run, to
    // the start cell's centre facing north; then a pause and the race
    heading = Direction::North;
    decided = true;
    then = Then::Race;
    return;
  }
  if (paths.phase() == PathManager<kMaxSide, kMaxSide>::Phase::SpeedRun && x == 0 && y == 0) {
    // home after exploring: stop in the start cell's centre, face north, and race
    push(Kind::Straight, kCell / 2, kSearch, 0);
    const int quarter = (static_cast<int>(heading) - static_cast<int>(Direction::North) + 4) % 4;
    if (quarter != 0) push(Kind::Pivot, 0, 0, 0, static_cast<int8_t>(quarter == 3 ? -1 : quarter));
    push(Kind::Pause, 0.3f, 0, 0);
    heading = Direction::North;
    decided = true;
    then = Then::Race;
    return;
  }
  if (a == Action::None) {
    push(Kind::Straight, kCell / 2, kSearch, 0);
    robot.log("no way to the goal");
    decided = true;
    then = Then::Finish;
    return;
  }
  uint8_t lastX = x, lastY = y;  // the cell whose far edge the queued segments reach
  if (a == Action::Forward) {
    // the cells ahead that are known on every side and that the plan crosses straight on hold
    // nothing to see: one faster straight crosses them, deciding at the last one's far edge
    // (their walls are known, so the plan there cannot change; the target's cells plan None)
    float length = kCell;
    for (;;) {
      const uint8_t aheadX = static_cast<uint8_t>(lastX + stepX(heading));
      const uint8_t aheadY = static_cast<uint8_t>(lastY + stepY(heading));
      if ((maze.cell(aheadX, aheadY) >> 4) != 0xF ||
          solver.bestAction(aheadX, aheadY, heading) != Action::Forward) {
        break;
      }
      lastX = aheadX;
      lastY = aheadY;
      length += kCell;
    }
    push(Kind::Straight, length, length > kCell ? kKnown : kSearch, kSearch, 0, true);
  } else {
    // the costs are those nextAction just worked out: a second flood fill (20 ms on a board)
    // would give the same
    const Direction h1 = turned(heading, a);
    const Action b = solver.bestAction(x, y, h1);
    if (b == Action::Forward) {
      const float vTurn = curveSpeed((kCell / 2 - kTurnStraight) / kTurnShape, kYawAccel);
      push(Kind::Straight, kTurnStraight, kSearch, vTurn);
      push(Kind::Curve, kCell / 2 - kTurnStraight, vTurn, vTurn, a == Action::TurnLeft ? 1 : -1);
      push(Kind::Straight, kTurnStraight, kSearch, kSearch, 0, true);
      heading = h1;
    } else {
      // turning round: stop in the cell's centre, pivot, and go back out
      const Direction h2 = b == Action::None ? turnAround(heading) : turned(h1, b);
      push(Kind::Straight, kCell / 2, kSearch, 0);
      const int8_t quarters = static_cast<int8_t>(a == Action::TurnLeft ? 2 : -2);
      push(Kind::Pivot, 0, 0, 0, quarters);
      push(Kind::Pause, 0.05f, 0, 0);
      push(Kind::Straight, kCell / 2, kSearch, kSearch, 0, true);
      heading = h2;
    }
  }
  nextX = static_cast<uint8_t>(lastX + stepX(heading));
  nextY = static_cast<uint8_t>(lastY + stepY(heading));
  decided = false;
}

// the maze as the simulator said (or the classic one), and every length at its scale
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
  } else {
    maze.resize(16, 16);
    robot.log("no maze from the simulator: a classic 16 x 16 maze, centre goal");
  }
  robot.reportMazeSize(maze.width(), maze.height());
  float* lengths[] = {&kCell,        &kWallFace, &kSensorAhead, &kSensorSide, &kWheelBase,
                      &kWheelRadius, &kAccel,    &kAccelRun,    &kLateral,    &kLateralHalfTurn,
                      &kTop,         &kSearch,   &kKnown,       &kSideWall,   &kFrontWall,
                      &kSenseFrom,   &kDecideAt, &kTurnStraight};
  for (float* l : lengths) *l *= kScale;
  // the half-size robot's short-range sensors read 0.1 m when they see nothing
  // (robots/unimouse-half.yaml): nearer than that a reading is a wall
  if (kScale < 1) kRange = 0.095f;
  filtered = kScale == 1;
  kFrontWall = fminf(kFrontWall, kRange);
  // a wheel's command per m/s and per m of travel: the same motor on a smaller wheel
  kSpeedFF /= kScale;
  kWheelP /= kScale;
  kWheelD /= kScale;
  trackSide = kTrackSide / kScale;
  perCount = 2 * PI * kWheelRadius / kCountsPerTurn;
  maze.placeWall(0, 0, Direction::East);
  maze.removeWall(0, 0, Direction::North);
  refX = estX = refY = estY = kCell / 2;
  estTheta = headingAngle(Direction::North);
  turnReference(estTheta);
}

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.requestMaze();  // before begin(): in lock-step the answer comes with the first step
  robot.begin();
}

void loop() {
  robot.update();
  // the loops run every kLoopMicros: on the PC each loop() is one 1 ms step; a board without
  // lock-step loops faster, and its encoder frames come once a millisecond
  const uint32_t now = micros();
  if (mode != Mode::AwaitMaze && now - lastMicros < kLoopMicros) return;
  float dt = (now - lastMicros) * 1e-6f;
  lastMicros = now;
  // a board that spent a while planning (a flood fill takes some 20 ms on a Mega 2560) catches up
  if (dt <= 0) dt = 0.001f;
  if (dt > 0.05f) dt = 0.05f;
  switch (mode) {
    case Mode::AwaitMaze:
      if (!robot.maze().received() && millis() < 1000) return;
      setupMaze();
      lastLeft = robot.leftEncoderTotal();
      lastRight = robot.rightEncoderTotal();
      mode = Mode::Calibrate;
      return;
    case Mode::Calibrate:
      // at rest: the gyro's bias, if the robot sends the gyro
      if (robot.imu().axis(2).hasNewData()) {
        hasGyro = true;
        gyroBias += robot.gyroZ();
        ++gyroSamples;
      }
      if (millis() < 1300) return;
      if (hasGyro) gyroBias /= gyroSamples;
      push(Kind::Straight, kCell / 2, kSearch, kSearch, 0, true);
      decided = false;
      mode = Mode::Run;
      return;
    case Mode::Run:
      break;
    case Mode::Done:
      robot.motorLeft(0);
      robot.motorRight(0);
      return;
  }
  updateEstimate(dt);
  correctEstimate();
  advanceReference(dt);
  // exploring: watch the cell ahead while approaching it, and decide before entering it
  if (!decided && !queueEmpty() && queue[head].sense && segmentStarted) {
    const float left = queue[head].length - refS;
    if (left < kSenseFrom) {
      minLeft = fminf(minLeft, robot.leftDistance());
      minRight = fminf(minRight, robot.rightDistance());
      minFront = fminf(minFront, robot.frontDistance());
    }
    if (left < kDecideAt) {
      queue[head].sense = false;
      decide();
    }
  }
  if (plan.active && queueRoom() >= 16) planMore();
  if (queueEmpty() && then == Then::Race) {
    then = Then::Finish;
    planSpeedRun();
  } else if (queueEmpty() && then == Then::Finish) {
    if (racing) {
      char line[40];
      snprintf(line, sizeof(line), "speed run 1: path cost %u", speedRunCost);
      robot.log(line);
    }
    finish(NULL);
    return;
  }
  control(dt);
}
