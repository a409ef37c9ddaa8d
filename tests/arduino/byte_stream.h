// SPDX-License-Identifier: GPL-3.0-or-later
// A Stream for tests of the firmware library: bytes "arrive" when the test says so, and
// available() shows only what has arrived; what the library writes is kept.
#ifndef UNIMOUSE_TESTS_ARDUINO_BYTE_STREAM_H_
#define UNIMOUSE_TESTS_ARDUINO_BYTE_STREAM_H_

#include <Arduino.h>

#include <deque>
#include <vector>

namespace unimouse {

class ByteStream : public Stream {
 public:
  void Arrive(const std::vector<uint8_t>& bytes) {
    in.insert(in.end(), bytes.begin(), bytes.end());
  }
  int available() override { return static_cast<int>(in.size()); }
  int read() override {
    if (in.empty()) return -1;
    const int b = in.front();
    in.pop_front();
    return b;
  }
  size_t write(uint8_t byte) override {
    out.push_back(byte);
    return 1;
  }

  std::deque<uint8_t> in;
  std::vector<uint8_t> out;
};

}  // namespace unimouse

#endif  // UNIMOUSE_TESTS_ARDUINO_BYTE_STREAM_H_
