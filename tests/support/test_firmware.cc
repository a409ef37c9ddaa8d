// SPDX-License-Identifier: GPL-3.0-or-later
// A firmware program for tests of the native link: it asks for lock-step, then answers every
// clock frame with motor commands (drive until the front sensor sees a wall within 0.3 m) and
// step-done.
//
//   --hang-at N          stop answering at step N, as a hung firmware would
//   --crash-at N         die of SIGABRT at step N (which the sanitizers leave alone)
//   --exit-at N          end with exit code 4 at step N
//   --report ID:ENC,...  report every frame with one of these ids (ENC tof, i16 or f32: how it
//                        reads) as a log line "rx ID STEP VALUE", STEP counting clock frames
//   --motors L,R         send these commands every step instead
//   --touch PATH         create the file PATH first, to show that it was started
//   --flood N            send N zero bytes first, as a firmware gone mad would
//   --flood-every-step N send N zero bytes before each step's answer
//   --leave-behind PATH  first start a process of its own session that outlives this one: it
//                        tries to create PATH, then sleeps 60 s (what a batch must not let live)
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
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

void Log(const std::string& text) {
  std::vector<uint8_t> frame = {UNIMOUSE_ID_LOG};
  frame.insert(frame.end(), text.begin(), text.end());
  frame.push_back(0);
  Send(frame);
}

// "3:i16,20:f32" -> id -> encoding
std::map<int, std::string> ParseReport(const char* text) {
  std::map<int, std::string> ids;
  std::string list = text;
  for (size_t at = 0; at < list.size();) {
    const size_t end = std::min(list.find(',', at), list.size());
    const std::string item = list.substr(at, end - at);
    const size_t colon = item.find(':');
    if (colon != std::string::npos) ids[std::atoi(item.c_str())] = item.substr(colon + 1);
    at = end + 1;
  }
  return ids;
}

// what a reported frame carries, as text
std::string Value(const std::string& encoding, const uint8_t* payload) {
  char text[48];
  if (encoding == "f32") {
    const uint32_t bits = unimouse_get_u32(payload);
    float f = 0;
    std::memcpy(&f, &bits, 4);
    std::snprintf(text, sizeof(text), "%.9g", static_cast<double>(f));
  } else if (encoding == "tof") {
    std::snprintf(text, sizeof(text), "%u", unimouse_get_u16(payload));
  } else {
    std::snprintf(text, sizeof(text), "%d", static_cast<int16_t>(unimouse_get_u16(payload)));
  }
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  long hang_at = -1;
  long crash_at = -1;
  long exit_at = -1;
  std::map<int, std::string> report;
  bool fixed_motors = false;
  int left = 0, right = 0;
  size_t junk_every_step = 0;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--flood-every-step") == 0) {
      junk_every_step = static_cast<size_t>(std::atol(argv[i + 1]));
    }
    if (std::strcmp(argv[i], "--hang-at") == 0) hang_at = std::atol(argv[i + 1]);
    if (std::strcmp(argv[i], "--crash-at") == 0) crash_at = std::atol(argv[i + 1]);
    if (std::strcmp(argv[i], "--exit-at") == 0) exit_at = std::atol(argv[i + 1]);
    if (std::strcmp(argv[i], "--report") == 0) report = ParseReport(argv[i + 1]);
    if (std::strcmp(argv[i], "--motors") == 0) {
      fixed_motors = std::sscanf(argv[i + 1], "%d,%d", &left, &right) == 2;
    }
    if (std::strcmp(argv[i], "--touch") == 0) {
      if (std::FILE* f = std::fopen(argv[i + 1], "w")) std::fclose(f);
    }
    if (std::strcmp(argv[i], "--leave-behind") == 0) {
      // two forks and a new session: no process group or parent of the firmware holds it
      const pid_t middle = ::fork();
      if (middle == 0) {
        ::setsid();
        if (::fork() == 0) {
          if (std::FILE* f = std::fopen(argv[i + 1], "w")) std::fclose(f);
          ::sleep(60);
        }
        ::_exit(0);
      }
      ::waitpid(middle, nullptr, 0);
    }
    if (std::strcmp(argv[i], "--flood") == 0) {
      Send(std::vector<uint8_t>(static_cast<size_t>(std::atol(argv[i + 1])), 0));
    }
  }
  Send({UNIMOUSE_ID_MANAGER, UNIMOUSE_MANAGER_LOCKSTEP_ON});
  Log("test firmware ready");
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
      const auto reported = report.find(pending[i]);
      const int size = reported == report.end()    ? unimouse_payload_size(pending[i])
                       : reported->second == "f32" ? 4
                                                   : 2;
      if (size < 0 || i + 1 + static_cast<size_t>(size) > pending.size()) break;
      if (reported != report.end()) {
        Log("rx " + std::to_string(pending[i]) + " " + std::to_string(step) + " " +
            Value(reported->second, &pending[i + 1]));
      }
      if (pending[i] == UNIMOUSE_ID_TOF_FRONT) front = unimouse_get_u16(&pending[i + 1]);
      if (pending[i] == UNIMOUSE_ID_CLOCK) {
        if (step == crash_at) std::abort();
        if (step == exit_at)
          std::_Exit(4);  // no exit handlers: a sanitizer's would change the code
        if (step++ == hang_at) {
          for (;;) ::pause();
        }
        if (junk_every_step > 0) Send(std::vector<uint8_t>(junk_every_step, 0));
        const int16_t speed =
            unimouse_tof_to_metres(front, UNIMOUSE_TOF_FULL_SCALE_M) > 0.3 ? 600 : 0;
        uint8_t f[8] = {
            UNIMOUSE_ID_MOTOR_LEFT,    0, 0, UNIMOUSE_ID_MOTOR_RIGHT, 0, 0, UNIMOUSE_ID_MANAGER,
            UNIMOUSE_MANAGER_STEP_DONE};
        unimouse_put_u16(f + 1, static_cast<uint16_t>(fixed_motors ? left : speed));
        unimouse_put_u16(f + 4, static_cast<uint16_t>(fixed_motors ? right : speed));
        Send({f, f + 8});
      }
      i += 1 + static_cast<size_t>(size);
    }
    pending.erase(pending.begin(), pending.begin() + static_cast<long>(i));
  }
}
