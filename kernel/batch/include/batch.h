// SPDX-License-Identifier: GPL-3.0-or-later
// `unimouse batch`: many runs from a manifest (docs/batch.md). Every job is one `unimouse batch
// job MANIFEST ID --out DIR` command line, whoever starts it: `batch run` (a local pool of
// workers), GNU parallel or a Slurm array over the lines `batch plan` writes. `batch collect`
// turns job directories into results.csv, results.json, summary.csv, junit.xml and report.html.
//
// Exit codes of run and collect: 0 every job passed, 1 some job did not pass, 2 a bad manifest
// or option, 3 interrupted (SIGINT, SIGTERM) or an internal error.
#ifndef UNIMOUSE_BATCH_BATCH_H_
#define UNIMOUSE_BATCH_BATCH_H_

#include <string>
#include <vector>

namespace unimouse::batch {

/// What `unimouse batch run` takes.
struct BatchOptions {
  std::string manifest;
  std::string out_dir = "batch-out";
  int workers = 0;      ///< jobs at once; 0 for one per core
  bool force = false;   ///< rerun jobs already done
  std::string program;  ///< the unimouse executable every job runs
  std::string version;  ///< unimouse's version, for the results
};

/// Runs a manifest's jobs that are not done yet, -j at a time, with progress on stdout; writes
/// the results for every done job, also when interrupted. Returns the exit code.
int RunBatch(const BatchOptions& options);

/// Writes out_dir/jobs.txt (one `unimouse batch job` line per job, absolute paths) and
/// out_dir/slurm-array.sh (a Slurm job array over those lines). Returns the exit code.
int PlanBatch(const std::string& manifest, const std::string& out_dir, const std::string& program);

/// Merges the job directories under `dirs` into results in out_dir. Returns the exit code.
int CollectBatch(const std::vector<std::string>& dirs, const std::string& out_dir,
                 const std::string& version);

/// Runs one job of a manifest (`unimouse batch job`). Returns the exit code.
int RunBatchJob(const std::string& manifest, const std::string& id, const std::string& out_dir,
                const std::string& program, const std::string& version);

/// Returns `word` quoted for a POSIX shell where it needs to be.
std::string ShellQuote(const std::string& word);

}  // namespace unimouse::batch

#endif  // UNIMOUSE_BATCH_BATCH_H_
