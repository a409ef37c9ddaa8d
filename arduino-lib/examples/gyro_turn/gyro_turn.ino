// SPDX-License-Identifier: MIT
// A 90-degree turn on the gyro, as competition mice turn: hold still while the gyro's bias is
// averaged (400 samples, as KERISE calibrates), then turn left under a PD controller on the
// angle, integrating the bias-corrected yaw rate every sample (angle += rate * Ts), and after
// 1.5 s log the angle the gyro saw. Run it on the gyro robot with the IMU's frame in the link's table:
//
//   unimouse run --robot unimouse-gyro --duration 3 --link native:gyro_turn --link-set
//     send='3 left.encoder_counts i16; 4 right.encoder_counts i16; 34 imu.gyro_z_counts i16'
#include <UnimouseSim.h>
#include <stdio.h>

SimulationRobot robot(Serial);

const float kSampleS = 0.001f;        // the IMU's output data rate: one frame a millisecond
const int kCalibrationSamples = 400;
const float kTargetRad = PI / 2;
const float kP = 700;   // command per radian of error
const float kD = 40;    // command per rad/s of yaw rate
const int32_t kMaxCommand = 350;
const int kTurnSamples = 1500;

enum State { kCalibrating, kTurning, kDone };
State state = kCalibrating;
int samples = 0;
float bias = 0, angle = 0;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
}

void loop() {
  robot.update();
  if (!robot.imu().axis(2).hasNewData()) return;
  const float rate = robot.gyroZ();
  switch (state) {
    case kCalibrating:
      bias += rate / kCalibrationSamples;
      if (++samples == kCalibrationSamples) {
        state = kTurning;
        samples = 0;
      }
      break;
    case kTurning: {
      angle += (rate - bias) * kSampleS;
      float command = kP * (kTargetRad - angle) - kD * (rate - bias);
      if (command > kMaxCommand) command = kMaxCommand;
      if (command < -kMaxCommand) command = -kMaxCommand;
      robot.motorLeft(static_cast<int32_t>(-command));
      robot.motorRight(static_cast<int32_t>(command));
      if (++samples == kTurnSamples) {
        robot.motorLeft(0);
        robot.motorRight(0);
        char text[48];
        const int tenths = static_cast<int>(angle * 1800 / PI + 0.5f);
        snprintf(text, sizeof(text), "gyro turn: %d.%d deg", tenths / 10, tenths % 10);
        robot.log(text);
        state = kDone;
      }
      break;
    }
    case kDone:
      break;
  }
}
