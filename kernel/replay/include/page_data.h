// SPDX-License-Identifier: GPL-3.0-or-later
// What the offline replay page (`unimouse replay ... --html`, kernel/report's replay page) shows,
// gathered from recordings: the scenery, each robot's path and footprint, chosen signals, events,
// log, beliefs, HUD and the firmware's values, as the JSON the page reads.
#ifndef UNIMOUSE_REPLAY_PAGE_DATA_H_
#define UNIMOUSE_REPLAY_PAGE_DATA_H_

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "recording.h"
#include "run_comparison.h"

namespace unimouse {

/// Most samples of a signal the page plots; a longer run is thinned evenly.
inline constexpr size_t kMaxPlotSamples = 4000;

/// The page's data for `recording`, with `ghosts` (another run's robots, a real robot's log)
/// drawn translucent beside it. `signals` names the signals to plot; empty: the motors'
/// voltages and currents, the encoders and the ToF sensors when the robot has them.
nlohmann::json ReplayPageData(const Recording& recording, const std::vector<RecordedRobot>& ghosts,
                              const std::vector<std::string>& signals,
                              const std::optional<Divergence>& divergence);

/// The length (along x, forward) and width of a robot's chassis from its file's text: the
/// extent of the chassis's box geoms; 0.12 x 0.10 m when the text is not a robot file.
std::pair<double, double> RobotFootprint(const std::string& robot_file_text);

}  // namespace unimouse

#endif  // UNIMOUSE_REPLAY_PAGE_DATA_H_
