// SPDX-License-Identifier: GPL-3.0-or-later
// The board's side of a link over a pseudo-terminal, for tests that play the firmware: raw
// bytes, never blocking.
#ifndef UNIMOUSE_TESTS_PTY_BOARD_H_
#define UNIMOUSE_TESTS_PTY_BOARD_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace unimouse::testing {

class PtyBoard {
 public:
  /// Opens the pty at `path` (what a pty link prints or links to), raw and non-blocking.
  explicit PtyBoard(const std::string& path) { Open(path); }
  ~PtyBoard() { Close(); }
  PtyBoard(const PtyBoard&) = delete;
  PtyBoard& operator=(const PtyBoard&) = delete;

  void Open(const std::string& path);
  void Close();
  int fd() const { return fd_; }
  /// Writes all of `bytes` to the simulator.
  void Send(std::vector<uint8_t> bytes);
  /// Sends both motor frames.
  void Motors(int16_t left, int16_t right);
  /// Returns every byte the simulator has sent since the last call.
  std::vector<uint8_t> Bytes();
  /// Reads everything the simulator has sent so far and counts its frames by id (ids whose
  /// size the protocol header gives).
  std::map<int, int> Drain();

 private:
  int fd_ = -1;
};

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_PTY_BOARD_H_
