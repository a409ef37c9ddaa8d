// SPDX-License-Identifier: MIT
// Answers every byte it receives with millis(), 4 bytes little-endian: the emulated board's
// clock against simulated time.
void setup() { Serial.begin(1000000); }

void loop() {
  if (Serial.available() > 0) {
    Serial.read();
    const uint32_t now = millis();
    for (int i = 0; i < 4; ++i) Serial.write(static_cast<uint8_t>(now >> (8 * i)));
  }
}
