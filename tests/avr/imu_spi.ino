// SPDX-License-Identifier: GPL-3.0-or-later
// An ordinary MPU-6500 driver on Arduino's SPI library, on the gyro robot: it reads WHO_AM_I at
// once (before the chip's 100 ms start-up) and again after it, wakes the chip, selects
// +-2000 dps, then calibrates the gyro's bias and turns 90 degrees left on gyro z read from the
// data registers every millisecond, and logs what it read and the angle it integrated. Chip
// select on digital pin 53 (PB0, the Mega 2560's SS). Built with IMU_SPI_NO_WAKE it forgets to
// write PWR_MGMT_1, a driver bug that a chip powering up asleep (the ICM-20602) shows.
#include <SPI.h>
#include <UnimouseSim.h>
#include <stdio.h>

SimulationRobot robot(Serial);
const uint8_t kSelect = 53;
const SPISettings kSpi(1000000, MSBFIRST, SPI_MODE3);

uint8_t readRegister(uint8_t address) {
  SPI.beginTransaction(kSpi);
  digitalWrite(kSelect, LOW);
  SPI.transfer(address | 0x80);
  const uint8_t value = SPI.transfer(0);
  digitalWrite(kSelect, HIGH);
  SPI.endTransaction();
  return value;
}

void writeRegister(uint8_t address, uint8_t value) {
  SPI.beginTransaction(kSpi);
  digitalWrite(kSelect, LOW);
  SPI.transfer(address);
  SPI.transfer(value);
  digitalWrite(kSelect, HIGH);
  SPI.endTransaction();
}

// gyro z from GYRO_ZOUT_H and _L, a burst of two
int16_t readGyroZ() {
  SPI.beginTransaction(kSpi);
  digitalWrite(kSelect, LOW);
  SPI.transfer(0x47 | 0x80);
  const uint8_t high = SPI.transfer(0);
  const uint8_t low = SPI.transfer(0);
  digitalWrite(kSelect, HIGH);
  SPI.endTransaction();
  return static_cast<int16_t>(static_cast<uint16_t>(high) << 8 | low);
}

void say(const char* format, int a, int b) {
  char text[64];
  snprintf(text, sizeof(text), format, a, b);
  robot.log(text);
}

const float kTargetRad = PI / 2;
const int kCalibrationSamples = 400;
int samples = 0;
float bias = 0, angle = 0;
bool calibrated = false, done = false;
uint32_t lastUs = 0;

void setup() {
  Serial.begin(UNIMOUSE_BAUD);
  robot.begin();
  pinMode(kSelect, OUTPUT);
  digitalWrite(kSelect, HIGH);
  SPI.begin();
  say("who_am_i at %d ms: 0x%02x", static_cast<int>(millis()), readRegister(0x75));
  robot.delay(150);
  say("who_am_i at %d ms: 0x%02x", static_cast<int>(millis()), readRegister(0x75));
#ifndef IMU_SPI_NO_WAKE
  writeRegister(0x6B, 0x01);  // PWR_MGMT_1: awake, best clock
#endif
  writeRegister(0x1A, 0x01);  // CONFIG: DLPF
  writeRegister(0x1B, 0x18);  // GYRO_CONFIG: +-2000 dps
  say("gyro_config: 0x%02x, pwr_mgmt_1: 0x%02x", readRegister(0x1B), readRegister(0x6B));
  robot.delay(50);  // the gyro's start-up
  lastUs = micros();
}

void loop() {
  robot.update();
  const uint32_t now = micros();
  if (done || now - lastUs < 1000) return;
  const float dt = (now - lastUs) * 1e-6f;
  lastUs = now;
  const float rate = readGyroZ() / 16.4f * PI / 180;
  if (!calibrated) {
    bias += rate / kCalibrationSamples;
    calibrated = ++samples == kCalibrationSamples;
    if (calibrated) samples = 0;
    return;
  }
  angle += (rate - bias) * dt;
  float command = 700 * (kTargetRad - angle) - 40 * (rate - bias);
  command = command > 350 ? 350 : command < -350 ? -350 : command;
  robot.motorLeft(static_cast<int32_t>(-command));
  robot.motorRight(static_cast<int32_t>(command));
  if (++samples == 1500) {
    robot.motorLeft(0);
    robot.motorRight(0);
    const int tenths = static_cast<int>(angle * 1800 / PI + 0.5f);
    say("spi gyro turn: %d.%d deg", tenths / 10, tenths % 10);
    done = true;
  }
}
