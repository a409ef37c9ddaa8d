// SPDX-License-Identifier: MIT
// What firmware needs of its sensors and motors, apart from where they are (dissertation figures
// 3.17 and 3.18, the adapter pattern): code written against these runs unchanged on the
// simulator's sensors and motors and on a real robot, where a small adapter class wraps the
// real driver (a VL53L0X library, an encoder interrupt counter, a motor shield).
#ifndef UNIMOUSE_SIM_DEVICES_H_
#define UNIMOUSE_SIM_DEVICES_H_

#include <stdint.h>

class IDistanceSensor {
 public:
  /// Metres to the nearest target; the sensor's full scale when there is none.
  virtual float distance() const = 0;

 protected:
  ~IDistanceSensor() = default;
};

class IEncoder {
 public:
  /// Counts since the start (32 bits, wrapping), positive forward.
  virtual int32_t count() const = 0;

 protected:
  ~IEncoder() = default;
};

class IMotor {
 public:
  /// Drives the motor: -1023..1023, positive forward.
  virtual void setCommand(int32_t command) = 0;

 protected:
  ~IMotor() = default;
};

#endif  // UNIMOUSE_SIM_DEVICES_H_
