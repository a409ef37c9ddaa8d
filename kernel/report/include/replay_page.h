// SPDX-License-Identifier: GPL-3.0-or-later
// A run's replay as one self-contained HTML page for a student: the scene seen from above at a
// cursor on a timeline, the firmware's beliefs, HUD and reported values at that time, plots of
// the recorded signals and the log near the cursor. The page needs no network and no other file:
// its script, style and data are all inside it, and its policy forbids fetching anything.
#ifndef UNIMOUSE_REPORT_REPLAY_PAGE_H_
#define UNIMOUSE_REPORT_REPLAY_PAGE_H_

#include <nlohmann/json.hpp>
#include <string>

namespace unimouse {

/// Returns the replay page of `data`, which has the shape
/// {"title", "end_s", "scenery": [{"kind", "x", "y", "size_x", "size_y", "yaw"}], "cell_m",
/// "robots": [{"name", "ghost", "source", "length_m", "width_m", "t": [], "x": [], "y": [],
/// "yaw": []}], "signals": {"t": [], "series": [{"name", "values": []}]},
/// "events": [{"t", "kind", "robot", "text"}], "log": [{"t", "level", "name", "message"}],
/// "beliefs": [{"t", "walls": [[x, y, walls, known]], "visited": [[x, y]], "path": [[x, y]],
/// "colours": [[x, y, "#rrggbb"]], "texts": [[x, y, text]]}], "hud": [{"t", "lines": []}],
/// "values": [{"t", "values": {name: number}}], "divergence": null or {"t", "distance_m", "text"}}
/// in metres, radians (yaw 0 east, counter-clockwise) and seconds. The data is written inside
/// the page as JSON that no text of it can end early (every '<' as \u003c); text that is not
/// UTF-8 is shown with replacement characters. The page opens at the cursor its address's
/// fragment names: `#t=12.5`, optionally `&speed=4`.
std::string ReplayPageHtml(const nlohmann::json& data);

/// Writes ReplayPageHtml(data) to `path` whole, through a temporary file, so that a reader never
/// sees half a page. Throws InputError "PATH: reason" when the file cannot be written.
void WriteReplayPage(const nlohmann::json& data, const std::string& path);

}  // namespace unimouse

#endif  // UNIMOUSE_REPORT_REPLAY_PAGE_H_
