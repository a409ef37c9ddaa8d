// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware program for tests of the native link: it asks for lock-step, then answers every
// clock frame with motor commands (drive until the front sensor sees a wall within 0.3 m) and
// step-done. `--hang-at N` makes it stop answering at step N, as a crashed firmware would.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "unimouse_protocol.h"

namespace {

void Send(const std::vector<uint8_t>& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(1, bytes.data() + done, bytes.size() - done);
    if (n <= 0) std::exit(1);
    done += static_cast<size_t>(n);
  }
}

}  // namespace

int main(int argc, char** argv) {
  long hang_at = -1;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--hang-at") == 0) hang_at = std::atol(argv[i + 1]);
  }
  Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON});
  const char hello[] = "test firmware ready";
  std::vector<uint8_t> log = {UNIMOUSE_ID_LOG};
  log.insert(log.end(), hello, hello + sizeof(hello));  // with its 0x00
  Send(log);
  // what it believes: the start cell's walls (east, south, west), the cells it expects, a plan
  Send({UNIMOUSE_ID_DEBUG_WALLS, 0, 0,
        UNIMOUSE_SIDE_EAST | UNIMOUSE_SIDE_SOUTH | UNIMOUSE_SIDE_WEST, 0x0F});
  Send({UNIMOUSE_ID_DEBUG_VISITED, 0, 0});
  Send({UNIMOUSE_ID_DEBUG_PATH, 3, 0, 0, 0, 1, 0, 2});
  const float speed_m_s = 1.5f;  // a named value: float32, then its name
  std::vector<uint8_t> value = {UNIMOUSE_ID_DEBUG_VALUE, 0, 0, 0, 0, 's', 'p', 'e', 'e', 'd', 0};
  std::memcpy(value.data() + 1, &speed_m_s, sizeof(speed_m_s));
  Send(value);

  std::vector<uint8_t> pending;
  uint16_t front = UNIMOUSE_TOF_NO_TARGET;
  long step = 0;
  uint8_t buffer[512];
  for (;;) {
    const ssize_t n = ::read(0, buffer, sizeof(buffer));
    if (n <= 0) return 0;  // the simulator went away
    pending.insert(pending.end(), buffer, buffer + n);
    size_t i = 0;
    while (i < pending.size()) {
      const int size = unimouse_payload_size(pending[i]);
      if (size < 0 || i + 1 + static_cast<size_t>(size) > pending.size()) break;
      if (pending[i] == UNIMOUSE_ID_TOF_FRONT) front = unimouse_get_u16(&pending[i + 1]);
      if (pending[i] == UNIMOUSE_ID_CLOCK) {
        if (step++ == hang_at) {
          for (;;) ::pause();
        }
        const int16_t speed =
            unimouse_tof_to_metres(front, UNIMOUSE_TOF_FULL_SCALE_M) > 0.3 ? 600 : 0;
        uint8_t f[8] = {
            UNIMOUSE_ID_MOTOR_LEFT,    0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0, UNIMOUSE_ID_MANAGER,
            UNIMOUSE_MANAGER_STEP_DONE};
        unimouse_put_u16(f + 1, static_cast<uint16_t>(speed));
        unimouse_put_u16(f + 4, static_cast<uint16_t>(speed));
        Send({f, f + 8});
      }
      i += 1 + static_cast<size_t>(size);
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<long>(i));
  }
}
