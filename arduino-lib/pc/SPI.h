// SPDX-License-Identifier: MIT
// Arduino's SPI library has no bus to drive on the PC: nothing is wired to the PC's pins.
#error \
    "SPI.h: the PC build has no SPI bus; build for the emulated board (unimouse firmware build SKETCH --board mega2560), where an SPI IMU can sit on the bus (docs/firmware.md)"
