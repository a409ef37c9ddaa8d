// SPDX-License-Identifier: GPL-3.0-or-later
// A batch manifest: the submissions, scenarios, mazes and seeds of a grading or comparison run,
// read strictly from YAML (docs/batch.md). Reading one starts no program and writes nothing: a
// scenario is loaded only as far as its top level, to learn its parameters.
//
//   submissions:
//     - name: alice
//       link: native:alice/firmware        # or controller: alice.lua; avr:FILE.elf; inproc:FILE.so
//     - name: bob
//       mms: python3 main.py                 # a program for the mms simulator: mazes only
//   scenarios:
//     - scenario: micromouse
//       set: {contest_s: 120}
//   mazes: [japan2018, contest/]           # bundled names, files, directories
//   seeds: [1, 2]
//   limits: {wall_time_s: 120, memory_mb: 2048}
#ifndef UNIMOUSE_BATCH_MANIFEST_H_
#define UNIMOUSE_BATCH_MANIFEST_H_

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "yaml_doc.h"

namespace unimouse::batch {

/// What one job may use; every value bounded (docs/batch.md, docs/limits.md).
struct JobLimits {
  double wall_time_s = 900;      ///< the job's processes are killed after this
  double cpu_time_s = 900;       ///< RLIMIT_CPU of the run (and what it starts)
  int memory_mb = 4096;          ///< RLIMIT_AS of each process
  int file_size_mb = 256;        ///< RLIMIT_FSIZE: the largest file a run may write
  std::string sandbox = "auto";  ///< auto (bwrap when it can sandbox here), bwrap, or none

  bool operator==(const JobLimits&) const = default;
};

/// One student's or strategy's entry: exactly one way to drive the robot, or a program written
/// for the mms simulator, which runs in the mazes without the scenarios (`unimouse mms`).
struct Submission {
  std::string name;                      ///< as written; its sanitised form names directories
  std::string link;                      ///< --link spec with absolute paths; "" with a controller
  std::string controller;                ///< absolute path of a Lua controller; "" with a link
  std::vector<std::string> mms;          ///< an mms program and its arguments; empty otherwise
  std::vector<std::string> mms_options;  ///< options of `unimouse mms`, as given
  std::string program_dir;               ///< the mms program's working directory (absolute)
  std::vector<std::string> link_sets;    ///< --link-set name=value
  std::string firmware_profile;          ///< --firmware-profile; "" for the default
  std::string robot;  ///< its own robot file (absolute) or bundled name; "" for the manifest's
  JobLimits limits;   ///< the manifest's limits, with this entry's overrides
  SourceLocation location;
};

/// A scenario with its parameters.
struct ScenarioEntry {
  std::string name;               ///< names directories: the scenario's own name unless given
  std::string file;               ///< scenario file (absolute) or bundled name
  std::vector<std::string> sets;  ///< --set name=value, in the manifest's order
  bool has_maze = false;          ///< whether the scenario has a `maze` parameter
  int min_robots = 1;             ///< the robots it needs (its `robots`): more than one, a race
  std::string default_maze;       ///< that parameter's default
  SourceLocation location;
};

/// One maze of the batch.
struct MazeEntry {
  std::string name;  ///< names directories: the file's stem
  std::string file;  ///< absolute path, or a bundled maze's file
};

/// The scenario column of an mms program's jobs.
inline constexpr const char* kMmsScenario = "mms";

/// One run of the batch: a submission (or several, each a robot of one world) in a scenario,
/// maze and seed.
struct Job {
  std::string id;           ///< submission/scenario/maze/seed-N, sanitised
  int submission = 0;       ///< index into Manifest::submissions
  std::vector<int> rivals;  ///< more submissions in the same world (a race), each a robot
  int scenario = 0;         ///< index into Manifest::scenarios; -1 for an mms program's job
  std::string maze;         ///< maze name; "" for a scenario without a maze parameter
  std::string maze_file;    ///< what --maze gets; "" for the scenario's own
  uint64_t seed = 1;
};

/// A manifest, read and checked, with every path absolute.
struct Manifest {
  std::string file;  ///< absolute path of the manifest
  std::string robot = "unimouse";
  /// --trace-period of every job: 0 (no trace) unless the manifest's `trace:` asks for one
  std::string trace_period_s = "0";
  std::string trace_signals;  ///< --trace-signals of every job; "" for the robot file's
  std::string rank_score;     ///< the score that ranks the submissions (`rank:`); "" for none
  std::vector<std::string> higher_is_better;  ///< scores better high (`higher_is_better:`)
  std::vector<Submission> submissions;
  std::vector<ScenarioEntry> scenarios;
  std::vector<Job> jobs;  ///< the product, or the explicit `jobs:` list; sorted by id
};

/// Most jobs one manifest may ask for.
inline constexpr size_t kMaxJobs = 100000;

/// Reads a manifest file; a mistake throws InputError with file:line:col.
Manifest LoadManifest(const std::string& path);

/// Returns `text` with every character outside [A-Za-z0-9._-] replaced by '_' (and "." or ".."
/// made "_"), for a directory name.
std::string SanitizeName(const std::string& text);

/// Returns the job's submission's name, or the names of all its submissions joined by '+'.
std::string SubmissionsName(const Manifest& manifest, const Job& job);

/// Returns the name of the job's scenario: its entry's, or "mms".
std::string ScenarioName(const Manifest& manifest, const Job& job);

/// Returns the job with this id, or throws InputError.
const Job& FindJob(const Manifest& manifest, const std::string& id);

/// Returns the arguments of the `unimouse run` that is the job (without the program name),
/// writing into out_dir.
std::vector<std::string> RunArguments(const Manifest& manifest, const Job& job,
                                      const std::string& out_dir);

}  // namespace unimouse::batch

#endif  // UNIMOUSE_BATCH_MANIFEST_H_
