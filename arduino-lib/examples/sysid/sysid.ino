// SPDX-License-Identifier: MIT
// The system-identification test pattern (docs/calibrate.md): a fixed sequence of H-bridge
// commands, open loop, logged as CSV over the robot's log every 10 ms for `unimouse fit`.
//
//   time_s,left_command,right_command,battery_v,left_counts,right_counts[,gyro_z_rad_s]
//
// time_s: seconds since the sequence started; *_command: the H-bridge command applied from this
// line until the next (-1023..1023); battery_v: the supply voltage the bridges switch;
// *_counts: encoder counts since the start, read at this line's time; gyro_z_rad_s: the IMU's
// yaw rate at this line's time, only when the robot's link sends the gyro's z frame
// (UNIMOUSE_ID_GYRO_Z; the sketch listens for it for 20 ms, so the first line is at 0.020 s).
// A lab can produce the same log from its own firmware: same columns, same order of reading and
// commanding.
//
// The sequence (about 50 s; it needs some 3 m of open floor each way):
//   standstill 1 s                  at rest: the zero of every channel, the gyro's bias
//   ramp forward 0 -> 700 in 8 s    quasi-static: speed per volt and Coulomb friction
//   rest 1.5 s, ramp backward 0 -> -700 in 8 s, rest 1.5 s
//   steps 100, 200, 300 forward and backward, 1.2 s on and 1.2 s off each: the speed's time
//                                   constant (Ra / Kt^2 times the inertia); small enough that
//                                   the wheels do not slip, which would make it the tyres'
//   spins in place 150 and 300 both ways, 1.5 s on and 1.5 s off: the same with the chassis'
//                                   yaw inertia; the gyro's scale
//   standstill 2 s                  at rest again
#include <UnimouseSim.h>
#include <stdio.h>

SimulationRobot robot(Serial);

const uint32_t kLogPeriodMs = 10;
// how long the sketch waits for the IMU's frames before it starts (they come every 1 ms)
const uint32_t kListenMs = 20;
// the supply the H-bridges switch; a real robot reads it (e.g. analogRead of a divider)
const int32_t kBatteryMillivolts = 6000;

struct Segment {
  uint32_t durationMs;
  int16_t leftFrom, leftTo;    // command at the start and at the end (a ramp when they differ)
  int16_t rightFrom, rightTo;
};

const Segment kSequence[] = {
    {1000, 0, 0, 0, 0},
    {8000, 0, 700, 0, 700},
    {1500, 0, 0, 0, 0},
    {8000, 0, -700, 0, -700},
    {1500, 0, 0, 0, 0},
    {1200, 100, 100, 100, 100},     {1200, 0, 0, 0, 0},
    {1200, -100, -100, -100, -100}, {1200, 0, 0, 0, 0},
    {1200, 200, 200, 200, 200},     {1200, 0, 0, 0, 0},
    {1200, -200, -200, -200, -200}, {1200, 0, 0, 0, 0},
    {1200, 300, 300, 300, 300},     {1200, 0, 0, 0, 0},
    {1200, -300, -300, -300, -300}, {1200, 0, 0, 0, 0},
    {1500, -150, -150, 150, 150},   {1500, 0, 0, 0, 0},
    {1500, 150, 150, -150, -150},   {1500, 0, 0, 0, 0},
    {1500, -300, -300, 300, 300},   {1500, 0, 0, 0, 0},
    {1500, 300, 300, -300, -300},   {1500, 0, 0, 0, 0},
    {2000, 0, 0, 0, 0},
};
const int kSegments = sizeof(kSequence) / sizeof(kSequence[0]);

int32_t leftCounts = 0, rightCounts = 0;
uint32_t startMs = 0, lastLogMs = 0;
bool started = false, logging = false, done = false, hasGyro = false;

int16_t interpolate(int16_t from, int16_t to, uint32_t intoMs, uint32_t durationMs) {
  return static_cast<int16_t>(from + (static_cast<int32_t>(to) - from) *
                                         static_cast<int32_t>(intoMs) /
                                         static_cast<int32_t>(durationMs));
}

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  // counts every step, so that none are lost between lines
  leftCounts += robot.leftEncoder();
  rightCounts += robot.rightEncoder();
  if (done) return;
  const uint32_t now = millis();
  if (!started) {
    started = true;
    startMs = now;
    lastLogMs = now - kLogPeriodMs;
  }
  // a robot whose link sends the gyro's z gets the column; one without keeps the log as it was
  if (!logging) hasGyro = robot.imu().axis(2).hasNewData() || hasGyro;
  if (now - lastLogMs < kLogPeriodMs) return;
  lastLogMs += kLogPeriodMs;
  const uint32_t t = lastLogMs - startMs;
  // the first rows go by at rest while the sketch listens; the time keeps counting from the
  // start, so that the log's time is the run's
  if (t < kListenMs) return;
  if (!logging) {
    logging = true;
    robot.log(hasGyro ? "time_s,left_command,right_command,battery_v,left_counts,right_counts,"
                        "gyro_z_rad_s"
                      : "time_s,left_command,right_command,battery_v,left_counts,right_counts");
  }

  // the segment this moment falls in
  uint32_t segmentStart = 0;
  int i = 0;
  while (i < kSegments && t >= segmentStart + kSequence[i].durationMs) {
    segmentStart += kSequence[i].durationMs;
    ++i;
  }
  int16_t left = 0, right = 0;
  if (i < kSegments) {
    const Segment& s = kSequence[i];
    left = interpolate(s.leftFrom, s.leftTo, t - segmentStart, s.durationMs);
    right = interpolate(s.rightFrom, s.rightTo, t - segmentStart, s.durationMs);
  }
  robot.motorLeft(left);
  robot.motorRight(right);

  char line[112];
  const int length = snprintf(line, sizeof(line), "%lu.%03lu,%d,%d,%ld.%03ld,%ld,%ld",
                        static_cast<unsigned long>(t / 1000), static_cast<unsigned long>(t % 1000),
                        left, right, static_cast<long>(kBatteryMillivolts / 1000),
                        static_cast<long>(kBatteryMillivolts % 1000), static_cast<long>(leftCounts),
                        static_cast<long>(rightCounts));
  if (hasGyro) {
    // in millionths of a rad/s, written as a decimal: the boards' printf has no %f
    const float rate = robot.gyroZ();
    const long micro = static_cast<long>(rate * 1e6f + (rate < 0 ? -0.5f : 0.5f));
    const unsigned long magnitude = static_cast<unsigned long>(micro < 0 ? -micro : micro);
    snprintf(line + length, sizeof(line) - length, ",%s%lu.%06lu", micro < 0 ? "-" : "",
             magnitude / 1000000UL, magnitude % 1000000UL);
  }
  robot.log(line);
  if (i >= kSegments) {
    robot.log("sysid done");
    done = true;
  }
}
