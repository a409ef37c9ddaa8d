// SPDX-License-Identifier: GPL-3.0-or-later
// The replay page's script and style (replay_page/replay.js, replay_page/replay.css), built into
// the library from their files at build time (CMakeLists.txt).
#ifndef UNIMOUSE_REPORT_REPLAY_PAGE_ASSETS_H_
#define UNIMOUSE_REPORT_REPLAY_PAGE_ASSETS_H_

#include <string_view>

namespace unimouse {

std::string_view ReplayPageScript();
std::string_view ReplayPageStyle();

}  // namespace unimouse

#endif  // UNIMOUSE_REPORT_REPLAY_PAGE_ASSETS_H_
