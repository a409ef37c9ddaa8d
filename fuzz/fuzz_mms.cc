// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes as the lines an mms program writes, answered one at a time by the protocol's logic
// tier in a bundled maze: every line gets a reply, no reply or a reason it was dropped, and what
// the program asked to display stays readable.
#include <cstddef>
#include <cstdint>
#include <string>

#include "maze.h"
#include "mms_protocol.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const unimouse::Maze maze = unimouse::LoadMaze(UNIMOUSE_FUZZ_MAZE);
  unimouse::MmsWorld world(maze, {});
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (size_t at = 0; at <= text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    world.Handle(text.substr(at, end - at));
    at = end + 1;
  }
  world.Display();
  world.Beliefs();
  return 0;
}
