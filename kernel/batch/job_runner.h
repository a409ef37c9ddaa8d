// SPDX-License-Identifier: GPL-3.0-or-later
// One job of a batch (`unimouse batch job`): the run as a child process in a process group of
// its own, under the job's limits (wall and CPU time, memory, file size, no core dumps) and,
// where bubblewrap is installed, with a read-only file system but for its job directory and no
// network. This process is the subreaper of whatever the run starts, so that nothing a
// submission forks outlives the job. The ending is classified and written to job.json. When
// the run left a recording (run.mcap), the job then writes the run's replay page beside it.
#ifndef UNIMOUSE_BATCH_JOB_RUNNER_H_
#define UNIMOUSE_BATCH_JOB_RUNNER_H_

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "manifest.h"

namespace unimouse::batch {

/// The job's replay page, in its directory: `unimouse replay DIR --html DIR/replay.html`.
inline constexpr char kReplayPage[] = "replay.html";

/// The wall-time limit of writing the replay page, unless the job's own limit is lower.
inline constexpr double kReplayWallTime_s = 120;

/// What the job saw of its run process.
struct ProcessEnd {
  bool timed_out = false;  ///< killed for running past the wall-time limit
  int exit_code = -1;      ///< -1 when ended by a signal
  int signal = 0;          ///< the signal that ended it, or 0
};

/// A job's status and why.
struct JobOutcome {
  std::string
      status;  ///< passed, failed, firmware_error, script_error, bad_input, timeout, crashed
  std::string reason;
};

/// Classifies a run's ending from what the job saw, the run's result.json (null when it wrote
/// none) and the limits it ran under.
JobOutcome ClassifyJob(const ProcessEnd& end, const nlohmann::json& result,
                       const JobLimits& limits);

/// Returns "SIGSEGV" for SIGSEGV, or "signal N".
std::string SignalName(int signal);

/// Returns the job's directory: batch_out/jobs/<id>.
std::string JobDirectory(const std::string& batch_out, const Job& job);

/// Returns every file the job reads (its submission's files, the scenario, the robot, the
/// maze), each as {role, file, sha256}; sha256 is "" for a file that cannot be read.
nlohmann::json JobInputs(const Manifest& manifest, const Job& job);

/// Returns what job.json records of how the job runs: the run's arguments, the limits and the
/// inputs with their SHA-256. A job whose job.json records the same is done (a batch resumes
/// without it): a changed submission, scenario, robot or maze file runs it again.
nlohmann::json JobCommand(const Manifest& manifest, const Job& job, const std::string& batch_out);

/// Whether the job's directory holds a job.json for exactly this job command.
bool JobIsDone(const Manifest& manifest, const Job& job, const std::string& batch_out);

/// A program's argv as execv() takes it, made before fork(): the child allocates nothing (under
/// a memory limit, a sanitizer's allocator could fail there and end it with its own exit code).
struct ExecArgs {
  explicit ExecArgs(const std::vector<std::string>& argv);
  ExecArgs(const ExecArgs&) = delete;  // the pointers point into this one's strings
  ExecArgs& operator=(const ExecArgs&) = delete;
  std::vector<std::string> strings;
  std::vector<char*> pointers;  ///< into strings, ended by nullptr
};

/// In a child process after fork(): makes it a process group of its own, reading /dev/null,
/// writing to out_fd and err_fd (/dev/null where -1), with SIGINT and SIGTERM as a program
/// expects them, and executes args (the first a path). Never returns.
[[noreturn]] void ExecInOwnGroup(const ExecArgs& args, int out_fd, int err_fd);

/// Runs one job and writes its job.json; returns 0 when it passed, 1 otherwise, 3 when it was
/// interrupted (SIGINT, SIGTERM: the run is stopped and no job.json is written). `program` is
/// the unimouse executable that runs `run`, and `replay` for the page of the run's recording
/// (under the same sandbox and limits); job.json names the page (`replay_page`), or says why
/// there is none (`replay_error`), which does not change the job's status.
int RunJob(const Manifest& manifest, const Job& job, const std::string& batch_out,
           const std::string& program, const std::string& version);

}  // namespace unimouse::batch

#endif  // UNIMOUSE_BATCH_JOB_RUNNER_H_
