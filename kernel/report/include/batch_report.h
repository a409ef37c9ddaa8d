// SPDX-License-Identifier: GPL-3.0-or-later
// A batch's results (results.json) as one self-contained HTML page for a teacher: the
// per-submission summary, the job table sortable by any column and filterable by status or text,
// and each job's pictures and replay page one click away. The page needs no network and no other
// file but those it links; its rows are plain HTML, so it reads without JavaScript, which only
// sorts and filters. Every text from the results (job reasons come from students' firmware) is
// escaped.
#ifndef UNIMOUSE_REPORT_BATCH_REPORT_H_
#define UNIMOUSE_REPORT_BATCH_REPORT_H_

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace unimouse {

/// Returns the report page of a batch's results, which have the shape of results.json:
/// {"unimouse_version", "manifest", "jobs": [{"id", "submission", "scenario", "maze", "seed",
/// "status", "reason", "scores": {name: value}, "sim_time_s", "wall_time_s", "exit_code", "dir",
/// "pictures": [path], "replay_page": path}], "summary": [{"submission", "jobs", "passed",
/// "failed", ..., "best", "mean_path_cost"}]}. Paths are relative to the page's directory. A
/// missing or null field shows as an empty cell. The page opens sorted and filtered as its
/// address's fragment says:
/// `#sort=wall_time_s` (a column's key; `-` before it for descending), `status=failed`,
/// `text=alice`, joined by `&`.
std::string BatchReportHtml(const nlohmann::json& results);

/// Writes BatchReportHtml(results) to `html` whole, through a temporary file, so that a reader
/// never sees half a page. Throws InputError when the file cannot be written.
void WriteBatchReport(const nlohmann::json& results, const std::filesystem::path& html);

}  // namespace unimouse

#endif  // UNIMOUSE_REPORT_BATCH_REPORT_H_
