// SPDX-License-Identifier: GPL-3.0-or-later
// The mms test clients (tests/mms/clients) as the command lines that start them.
#ifndef UNIMOUSE_TESTS_MMS_CLIENTS_H_
#define UNIMOUSE_TESTS_MMS_CLIENTS_H_

#include <string>

namespace unimouse::testing {

/// The flood fill, in C++ with the mms C++ API.
inline const std::string kFloodFillClient = UNIMOUSE_MMS_FLOODFILL;
/// The left-wall follower, in Python, started by Debian's python3 by its path: a version
/// manager's shim on PATH may cost more than the run.
inline const std::string kLeftWallClient =
    UNIMOUSE_PYTHON3 " " UNIMOUSE_SOURCE_DIR "/tests/mms/clients/left_wall.py";

}  // namespace unimouse::testing

#endif  // UNIMOUSE_TESTS_MMS_CLIENTS_H_
