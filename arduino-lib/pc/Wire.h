// SPDX-License-Identifier: MIT
// Arduino's Wire library has no bus to drive on the PC: nothing is wired to the PC's pins.
#error \
    "Wire.h: the PC build has no I2C bus, and no part of the simulated robot sits on one; an IMU can sit on the emulated board's SPI bus (docs/firmware.md)"
