// SPDX-License-Identifier: MIT
// Speed control (dissertation section 5.1.1, algorithm 3): drive at 1 m/s while turning at
// 2 rad/s counter-clockwise. Every 20 ms the encoders give the wheels' speeds, hence the robot's
// (eq. 3.26, 3.28); a base command integrates the linear speed's error and an offset between
// the wheels integrates the angular speed's. (Algorithm 3 as printed subtracts the target from
// the measurement, which with positive gains pushes away from the target; this is the intended
// sign.)
#include <UnimouseSim.h>

SimulationRobot robot(Serial);
const RobotConstructionSpecification spec;

const float kSpeed = 1.0f;     // m/s
const float kTurnRate = 2.0f;  // rad/s, counter-clockwise
const uint32_t kSampleMs = 20;
const float kBaseGain = 10.0f;   // command per (m/s of error) per sample
const float kOffsetGain = 2.0f;  // command per (rad/s of error) per sample

float base = 0, offset = 0;
uint32_t lastMs = 0;

float clampCommand(float c) { return c > 1023 ? 1023 : c < -1023 ? -1023 : c; }

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  const uint32_t now = millis();
  if (now - lastMs < kSampleMs) return;
  const float dt = (now - lastMs) / 1000.0f;
  lastMs = now;
  const float left = robot.leftEncoder() * 2 * PI * spec.leftWheelRadius / spec.leftWheelCPR / dt;
  const float right =
      robot.rightEncoder() * 2 * PI * spec.rightWheelRadius / spec.rightWheelCPR / dt;
  const float speed = (right + left) / 2;                         // eq. 3.28
  const float turnRate = (right - left) / spec.wheelBaseDistance;  // eq. 3.26
  // integrals held within what the motors can do, so that they do not wind up
  base = clampCommand(base + (kSpeed - speed) * kBaseGain);
  offset = clampCommand(offset + (kTurnRate - turnRate) * kOffsetGain);
  robot.motorLeft(static_cast<int32_t>(base - offset));
  robot.motorRight(static_cast<int32_t>(base + offset));
}
