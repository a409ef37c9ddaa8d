/* SPDX-License-Identifier: MIT */
/* The UnimouseSim link protocol: the one source of frame ids, payload sizes and scaling, shared
 * by the simulator and the Arduino library. docs/protocol.md specifies it byte by byte.
 *
 * A frame is [id][payload], little-endian, with no start byte, length or checksum; the id
 * implies the payload's length (ids 0-8 as in the original UnimouseSim). Ids 9 and up are
 * extensions: the simulator sends extension frames only after the firmware asks for them with
 * a manager byte, so firmware written for the original never sees them. Plain C, no heap. */
#ifndef UNIMOUSE_PROTOCOL_H_
#define UNIMOUSE_PROTOCOL_H_

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* frame ids */
enum {
  UNIMOUSE_ID_TOF_LEFT = 0,      /* sim -> MCU, uint16: left ToF, 45 degrees */
  UNIMOUSE_ID_TOF_RIGHT = 1,     /* sim -> MCU, uint16: right ToF, 45 degrees */
  UNIMOUSE_ID_TOF_FRONT = 2,     /* sim -> MCU, uint16: front ToF */
  UNIMOUSE_ID_ENCODER_LEFT = 3,  /* sim -> MCU, int16: counts since the previous frame */
  UNIMOUSE_ID_ENCODER_RIGHT = 4, /* sim -> MCU, int16 */
  UNIMOUSE_ID_MOTOR_LEFT = 5,    /* MCU -> sim, int16: H-bridge command, -1023..1023 */
  UNIMOUSE_ID_MOTOR_RIGHT = 6,   /* MCU -> sim, int16 */
  UNIMOUSE_ID_MANAGER = 7,       /* MCU -> sim, 1 byte: a UNIMOUSE_MANAGER_* code */
  UNIMOUSE_ID_LOG = 8,           /* MCU -> sim, text bytes ended by 0x00 */
  /* extensions */
  UNIMOUSE_ID_CLOCK = 9,          /* sim -> MCU, uint32: sim time in us; the step's frames are in */
  UNIMOUSE_ID_DEBUG_WALLS = 10,   /* MCU -> sim, 4 bytes: x, y, walls, known (UNIMOUSE_SIDE_*) */
  UNIMOUSE_ID_DEBUG_VISITED = 11, /* MCU -> sim, 2 bytes: x, y */
  UNIMOUSE_ID_DEBUG_PATH = 12,    /* MCU -> sim, n, then n pairs x, y: the path it plans */
  UNIMOUSE_ID_DEBUG_VALUE = 13,   /* MCU -> sim, float32, then a name ended by 0x00 */
  UNIMOUSE_ID_MAZE_INFO = 14,     /* sim -> MCU, 8 bytes, once asked (UNIMOUSE_MANAGER_MAZE_INFO):
                                     width, height (cells; 0 0 without a maze), cell side in mm
                                     (uint16), goal rectangle x0, y0, x1, y1 (inclusive) */
  UNIMOUSE_ID_MAZE_SIZE = 15,     /* MCU -> sim, 2 bytes: the width and height of the maze the
                                     firmware works with; the simulator warns if they differ */
  /* an IMU's raw register counts, int16, as the chip's data registers hold them (the robot's
   * send table names them, e.g. "34 imu.gyro_z_counts i16"; robots/unimouse-gyro.yaml) */
  UNIMOUSE_ID_GYRO_X = 32, /* sim -> MCU, int16 */
  UNIMOUSE_ID_GYRO_Y = 33,
  UNIMOUSE_ID_GYRO_Z = 34,
  UNIMOUSE_ID_ACCEL_X = 35,
  UNIMOUSE_ID_ACCEL_Y = 36,
  UNIMOUSE_ID_ACCEL_Z = 37,
  UNIMOUSE_ID_FRAME_SIZE = 127 /* sim -> MCU, 2 bytes, once asked (UNIMOUSE_MANAGER_FRAME_SIZES):
                                  a data frame's id and its payload bytes, one frame for each
                                  entry of the link's send table that the protocol does not size
                                  itself, so that the firmware can step over frames it has no
                                  sensor for (a robot's extra sensor) */
};

/* manager codes */
enum {
  UNIMOUSE_MANAGER_STOP = 0x00,
  UNIMOUSE_MANAGER_START = 0x01,
  UNIMOUSE_MANAGER_SENSORS_ON = 0x02,
  UNIMOUSE_MANAGER_SENSORS_OFF = 0x03,
  /* extensions */
  UNIMOUSE_MANAGER_LOCKSTEP_ON = 0x10,      /* from the next step on, the simulator sends a clock
                                               frame after each step's sensor frames and waits */
  UNIMOUSE_MANAGER_STEP_DONE = 0x11,        /* the firmware has sent everything for this step */
  UNIMOUSE_MANAGER_REPEATS_COMMANDS = 0x12, /* the firmware resends its motor commands at least
                                              every 50 ms, so silence means it is in trouble:
                                              the simulator stops the motors after failsafe_s */
  UNIMOUSE_MANAGER_MAZE_INFO = 0x13,        /* the simulator answers with one maze info frame */
  UNIMOUSE_MANAGER_FRAME_SIZES = 0x14       /* the simulator answers with a frame size frame
                                               for each data frame it sends */
};

/* begin() of this project's library opens with these three manager codes, in this order; the
 * simulator takes them arriving again mid-run as the firmware starting over (docs/protocol.md,
 * "Restarts") */
#define UNIMOUSE_STARTUP_CODES \
  { UNIMOUSE_MANAGER_FRAME_SIZES, UNIMOUSE_MANAGER_SENSORS_ON, UNIMOUSE_MANAGER_REPEATS_COMMANDS }

/* sides in a debug walls frame: bits of `walls` and `known` */
enum {
  UNIMOUSE_SIDE_NORTH = 0x01,
  UNIMOUSE_SIDE_EAST = 0x02,
  UNIMOUSE_SIDE_SOUTH = 0x04,
  UNIMOUSE_SIDE_WEST = 0x08
};

#define UNIMOUSE_MOTOR_MAX 1023       /* 10-bit magnitude, sign-magnitude H-bridge */
#define UNIMOUSE_TOF_NO_TARGET 0xFFFF /* no target, or out of range */
#define UNIMOUSE_TOF_FULL_SCALE_M 1.2 /* VL53L0X maximum range (dissertation table 3.8) */
#define UNIMOUSE_LOG_MAX 255          /* longest log line; longer ones are cut there */
/* the line rate to open Serial at: exact at 16 MHz (UBRR 1 with U2X), and room for a 1 kHz
 * stream; 115200 baud cannot carry one in lock-step (eq. 4.1: 11 bytes a step take 0.95 ms) */
#define UNIMOUSE_BAUD 1000000UL
#define UNIMOUSE_FRAME_VARIABLE (-1)

/* Payload bytes of a frame, UNIMOUSE_FRAME_VARIABLE for logs, paths and values, -2 for an id
 * nobody defines. */
static inline int unimouse_payload_size(uint8_t id) {
  switch (id) {
    case UNIMOUSE_ID_TOF_LEFT:
    case UNIMOUSE_ID_TOF_RIGHT:
    case UNIMOUSE_ID_TOF_FRONT:
    case UNIMOUSE_ID_ENCODER_LEFT:
    case UNIMOUSE_ID_ENCODER_RIGHT:
    case UNIMOUSE_ID_MOTOR_LEFT:
    case UNIMOUSE_ID_MOTOR_RIGHT:
      return 2;
    case UNIMOUSE_ID_MANAGER:
      return 1;
    case UNIMOUSE_ID_CLOCK:
      return 4;
    case UNIMOUSE_ID_DEBUG_WALLS:
      return 4;
    case UNIMOUSE_ID_DEBUG_VISITED:
    case UNIMOUSE_ID_MAZE_SIZE:
    case UNIMOUSE_ID_GYRO_X:
    case UNIMOUSE_ID_GYRO_Y:
    case UNIMOUSE_ID_GYRO_Z:
    case UNIMOUSE_ID_ACCEL_X:
    case UNIMOUSE_ID_ACCEL_Y:
    case UNIMOUSE_ID_ACCEL_Z:
      return 2;
    case UNIMOUSE_ID_MAZE_INFO:
      return 8;
    case UNIMOUSE_ID_FRAME_SIZE:
      return 2;
    case UNIMOUSE_ID_LOG:
    case UNIMOUSE_ID_DEBUG_PATH:
    case UNIMOUSE_ID_DEBUG_VALUE:
      return UNIMOUSE_FRAME_VARIABLE;
    default:
      return -2;
  }
}

/* ToF reading to counts: round(d / full_scale * 65535); 0xFFFF at or beyond full scale. */
static inline uint16_t unimouse_tof_to_counts(double distance_m, double full_scale_m) {
  if (!(distance_m < full_scale_m)) return UNIMOUSE_TOF_NO_TARGET;
  if (distance_m <= 0) return 0;
  return (uint16_t)(distance_m / full_scale_m * 65535.0 + 0.5);
}

/* Counts to metres; UNIMOUSE_TOF_NO_TARGET gives the full scale. */
static inline double unimouse_tof_to_metres(uint16_t counts, double full_scale_m) {
  return counts * full_scale_m / 65535.0;
}

static inline void unimouse_put_u16(uint8_t* out, uint16_t v) {
  out[0] = (uint8_t)(v & 0xFF);
  out[1] = (uint8_t)(v >> 8);
}

static inline uint16_t unimouse_get_u16(const uint8_t* in) {
  return (uint16_t)(in[0] | (uint16_t)in[1] << 8);
}

static inline void unimouse_put_u32(uint8_t* out, uint32_t v) {
  out[0] = (uint8_t)(v & 0xFF);
  out[1] = (uint8_t)(v >> 8 & 0xFF);
  out[2] = (uint8_t)(v >> 16 & 0xFF);
  out[3] = (uint8_t)(v >> 24);
}

static inline uint32_t unimouse_get_u32(const uint8_t* in) {
  return (uint32_t)in[0] | (uint32_t)in[1] << 8 | (uint32_t)in[2] << 16 | (uint32_t)in[3] << 24;
}

/* Motor command clamped to [-UNIMOUSE_MOTOR_MAX, UNIMOUSE_MOTOR_MAX]. */
static inline int16_t unimouse_clamp_motor(int32_t command) {
  if (command > UNIMOUSE_MOTOR_MAX) return UNIMOUSE_MOTOR_MAX;
  if (command < -UNIMOUSE_MOTOR_MAX) return -UNIMOUSE_MOTOR_MAX;
  return (int16_t)command;
}

#ifdef __cplusplus
}
#endif

#endif /* UNIMOUSE_PROTOCOL_H_ */
