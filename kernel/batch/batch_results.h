// SPDX-License-Identifier: GPL-3.0-or-later
// A batch's results from its job directories (each job.json): results.json and results.csv
// (a row per job, sorted by job id), summary.csv (a row per submission), junit.xml (a
// testsuite per submission, a testcase per job) and report.html (the page a teacher opens). The
// same files however the jobs ran: `batch run`, GNU parallel or a Slurm array, merged by `batch
// collect`.
#ifndef UNIMOUSE_BATCH_BATCH_RESULTS_H_
#define UNIMOUSE_BATCH_BATCH_RESULTS_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace unimouse::batch {

/// Every status a job can end with, in the order summaries list them.
inline const std::vector<std::string> kStatuses = {
    "passed", "failed", "firmware_error", "script_error", "bad_input", "timeout", "crashed"};

/// Returns the rows of results.json for these job directories (each holding a job.json):
/// sorted by id, `dir`, `pictures` and `replay_page` (null when the job has none) relative to
/// out_dir. Throws InputError when two directories hold the same job.
nlohmann::json JobRows(const std::vector<std::string>& job_dirs, const std::string& out_dir);

/// Returns every directory under `root` (itself included) that holds a job.json, sorted.
std::vector<std::string> FindJobDirectories(const std::string& root);

/// Which score ranks the submissions, and which scores are better high (the others are better
/// low), as a manifest declares them (`rank:`, `higher_is_better:`).
struct ScoreRanking {
  std::string score;                          ///< "" for no ranking
  std::vector<std::string> higher_is_better;  ///< score names
};

/// Returns the per-submission summary of job rows: jobs and a count per status, the best
/// passed job (lowest best_run_s score, else lowest sim time), the mean of the
/// best_run_path_cost scores (null when no job reports one), and for every score any of its
/// jobs reports `scores: {name: {jobs, mean, best, worst}}` (best and worst by the ranking's
/// direction for that score). With a ranking score, each submission's `rank` (1 the best, by its
/// best value of that score; null without one), and the list in rank order.
nlohmann::json Summarize(const nlohmann::json& rows, const ScoreRanking& ranking = {});

/// Writes results.json (with the ranking as `rank`), results.csv, summary.csv, junit.xml and
/// report.html into out_dir.
void WriteResults(const std::string& out_dir, const nlohmann::json& rows,
                  const std::string& manifest, const std::string& version,
                  const ScoreRanking& ranking = {});

}  // namespace unimouse::batch

#endif  // UNIMOUSE_BATCH_BATCH_RESULTS_H_
