// SPDX-License-Identifier: GPL-3.0-or-later
#include "batch.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <thread>

#include "batch_results.h"
#include "job_runner.h"
#include "manifest.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t stop_signal = 0;

void OnStop(int signal) { stop_signal = signal; }

std::string JobLine(const std::string& program, const Manifest& m, const Job& job,
                    const std::string& out) {
  return ShellQuote(program) + " batch job " + ShellQuote(m.file) + " " + ShellQuote(job.id) +
         " --out " + ShellQuote(out);
}

// "m:ss" for a time left
std::string MinutesSeconds(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  std::snprintf(text, sizeof(text), "%ld:%02ld", s / 60, s % 60);
  return text;
}

// the status a job.json records, or "" when it cannot be read
std::string JobStatus(const std::string& dir) {
  try {
    return nlohmann::json::parse(ReadTextFile(dir + "/job.json")).value("status", "");
  } catch (const std::exception&) {
    return "";
  }
}

// results from the jobs of this manifest that are done with its current command
int WriteManifestResults(const Manifest& m, const std::string& out, const std::string& version,
                         int* not_passed) {
  std::vector<std::string> dirs;
  for (const auto& job : m.jobs) {
    if (JobIsDone(m, job, out)) dirs.push_back(JobDirectory(out, job));
  }
  const nlohmann::json rows = JobRows(dirs, out);
  WriteResults(out, rows, m.file, version, {m.rank_score, m.higher_is_better});
  *not_passed = 0;
  for (const auto& row : rows) *not_passed += row["status"] != "passed";
  return static_cast<int>(rows.size());
}

}  // namespace

std::string ShellQuote(const std::string& word) {
  const bool plain = !word.empty() && word.find_first_not_of(
                                          "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789_/.:=@%+,-") == std::string::npos;
  if (plain) return word;
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

int RunBatch(const BatchOptions& o) {
  const Manifest m = LoadManifest(o.manifest);
  const std::string out = fs::absolute(o.out_dir).lexically_normal().string();
  fs::create_directories(out);
  const int workers = o.workers > 0
                          ? o.workers
                          : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  if (o.force) {
    // forgotten before anything runs: an interrupted --force leaves no old result among the new
    for (const auto& job : m.jobs) fs::remove_all(JobDirectory(out, job));
  }
  std::vector<const Job*> queue;
  int done = 0, passed = 0;
  for (const auto& job : m.jobs) {
    if (!o.force && JobIsDone(m, job, out)) {
      ++done;
      passed += JobStatus(JobDirectory(out, job)) == "passed";
    } else {
      queue.push_back(&job);
    }
  }
  const int total = static_cast<int>(m.jobs.size());
  const bool terminal = ::isatty(1) != 0;
  std::printf("unimouse batch: %d jobs, %d to run, %d at a time, into %s\n", total,
              static_cast<int>(queue.size()), workers, out.c_str());
  if (done > 0) {
    std::printf(
        "  %d already done with the same inputs (SHA-256 of submission, scenario, robot and "
        "maze), kept (--force runs them again)\n",
        done);
  }
  std::fflush(stdout);

  // no SA_RESTART: a signal wakes the wait below
  struct sigaction action = {};
  action.sa_handler = OnStop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  const std::string log = (fs::path(out) / "batch.log").string();
  struct Running {
    const Job* job;
    Clock::time_point start;
  };
  std::map<pid_t, Running> running;
  size_t next = 0;
  double finished_wall_s = 0;
  int finished = 0;
  const auto start = Clock::now();
  std::optional<Clock::time_point> stop_asked;
  for (;;) {
    while (stop_signal == 0 && next < queue.size() && static_cast<int>(running.size()) < workers) {
      const Job& job = *queue[next++];
      const ExecArgs args({o.program, "batch", "job", m.file, job.id, "--out", out});
      const pid_t pid = ::fork();
      UNIMOUSE_THROW_UNLESS(pid >= 0, "cannot start a process for job " + job.id);
      if (pid == 0) {
        // its own process group: a terminal's Ctrl-C reaches this process only, which stops
        // the jobs in order
        ExecInOwnGroup(args, -1,
                       ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644));
      }
      ::setpgid(pid, pid);
      running[pid] = {&job, Clock::now()};
    }
    if (running.empty()) break;
    if (stop_signal != 0 && !stop_asked) {
      stop_asked = Clock::now();
      std::printf("%sunimouse batch: %s: stopping %zu running job%s\n", terminal ? "\n" : "",
                  SignalName(stop_signal).c_str(), running.size(), running.size() == 1 ? "" : "s");
      std::fflush(stdout);
      for (const auto& [pid, r] : running) ::kill(pid, SIGTERM);
    }
    if (stop_asked && Clock::now() - *stop_asked > std::chrono::seconds(10)) {
      for (const auto& [pid, r] : running) ::kill(-pid, SIGKILL);
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, stop_asked ? WNOHANG : 0);
    if (pid <= 0) {
      if (stop_asked) std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    if (stop_asked) continue;  // an interrupted job leaves no record
    const double wall_s = std::chrono::duration<double>(Clock::now() - r.start).count();
    finished_wall_s += wall_s;
    ++finished;
    ++done;
    std::string what = JobStatus(JobDirectory(out, *r.job));
    if (what.empty()) {
      what = "no record (batch job exit code " +
             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ", see batch.log)";
    }
    passed += what == "passed";
    // what is left, spread over the workers, at the mean time of a job so far
    const double left = static_cast<double>(queue.size() - next + running.size());
    const double eta_s = finished_wall_s / finished * left / workers;
    if (terminal) {
      std::printf("\r\033[K[%d/%d] %d passed, %d not passed, %zu running, ETA %s", done, total,
                  passed, done - passed, running.size(), MinutesSeconds(eta_s).c_str());
    } else {
      std::printf("[%d/%d] %s: %s (%.1f s)\n", done, total, r.job->id.c_str(), what.c_str(),
                  wall_s);
    }
    std::fflush(stdout);
  }
  if (terminal) std::printf("\n");

  int not_passed = 0;
  const int recorded = WriteManifestResults(m, out, o.version, &not_passed);
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("unimouse batch: %d of %d jobs done, %d passed, %d not passed, %.1f s\n", recorded,
              total, recorded - not_passed, not_passed, wall_s);
  std::printf(
      "  report: %s/report.html (also results.csv, results.json, summary.csv, "
      "junit.xml)\n",
      out.c_str());
  if (stop_signal != 0) {
    std::printf("  interrupted: run the same command again to go on where it stopped\n");
    return kExitRuntimeFault;
  }
  if (recorded < total) return kExitRuntimeFault;  // a job that could not run at all
  return not_passed == 0 ? kExitPassed : kExitFailed;
}

int PlanBatch(const std::string& manifest, const std::string& out_dir, const std::string& program) {
  const Manifest m = LoadManifest(manifest);
  const std::string out = fs::absolute(out_dir).lexically_normal().string();
  fs::create_directories(fs::path(out) / "slurm");
  std::string lines;
  double wall_s = 0;
  int memory_mb = 0;
  for (const auto& job : m.jobs) {
    lines += JobLine(program, m, job, out) + "\n";
    const JobLimits& l = m.submissions[static_cast<size_t>(job.submission)].limits;
    wall_s = std::max(wall_s, l.wall_time_s);
    memory_mb = std::max(memory_mb, l.memory_mb);
  }
  const std::string jobs_txt = (fs::path(out) / "jobs.txt").string();
  WriteTextFile(jobs_txt, lines);
  // a minute more than the longest job for starting and ending it
  const long minutes = static_cast<long>(std::ceil((wall_s + 60) / 60));
  const std::string script =
      "#!/bin/bash\n"
      "# Written by `unimouse batch plan`: one Slurm array task per line of jobs.txt.\n"
      "#   sbatch " +
      ShellQuote(out + "/slurm-array.sh") +
      "\n"
      "# then, when every task has ended: unimouse batch collect " +
      ShellQuote(out) +
      "\n"
      "#SBATCH --job-name=unimouse-batch\n"
      "#SBATCH --array=1-" +
      std::to_string(m.jobs.size()) +
      "\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task=1\n"
      "#SBATCH --mem=" +
      std::to_string(memory_mb) +
      "M\n"
      "#SBATCH --time=" +
      std::to_string(minutes) +
      "\n"
      "#SBATCH --output=" +
      out +
      "/slurm/%A_%a.out\n"
      "set -eu\n"
      "line=$(sed -n \"${SLURM_ARRAY_TASK_ID}p\" " +
      ShellQuote(jobs_txt) +
      ")\n"
      "if [ -z \"$line\" ]; then\n"
      "  echo \"jobs.txt has no line ${SLURM_ARRAY_TASK_ID}\" >&2\n"
      "  exit 2\n"
      "fi\n"
      "eval \"exec $line\"\n";
  const fs::path script_file = fs::path(out) / "slurm-array.sh";
  WriteTextFile(script_file.string(), script);
  fs::permissions(script_file,
                  fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                  fs::perm_options::add);
  std::printf(
      "unimouse batch plan: %zu jobs\n  %s (GNU parallel: parallel -j N < %s)\n  %s "
      "(Slurm: sbatch %s)\n  then: unimouse batch collect %s\n",
      m.jobs.size(), jobs_txt.c_str(), ShellQuote(jobs_txt).c_str(), script_file.c_str(),
      ShellQuote(script_file.string()).c_str(), ShellQuote(out).c_str());
  return kExitPassed;
}

int CollectBatch(const std::vector<std::string>& dirs, const std::string& out_dir,
                 const std::string& version) {
  std::vector<std::string> job_dirs;
  for (const auto& d : dirs) {
    for (auto& j : FindJobDirectories(d)) job_dirs.push_back(std::move(j));
  }
  UNIMOUSE_THROW_UNLESS(!job_dirs.empty(),
                        "no job directories (with a job.json) in the "
                        "directories given");
  const std::string out = out_dir.empty() ? dirs.front() : out_dir;
  const nlohmann::json rows = JobRows(job_dirs, out);
  const std::string manifest =
      nlohmann::json::parse(ReadTextFile(job_dirs.front() + "/job.json")).value("manifest", "");
  // the manifest's ranking, when it is still where the jobs ran it from
  ScoreRanking ranking;
  try {
    const Manifest m = LoadManifest(manifest);
    ranking = {m.rank_score, m.higher_is_better};
  } catch (const std::exception&) {
  }
  WriteResults(out, rows, manifest, version, ranking);
  int not_passed = 0;
  for (const auto& row : rows) not_passed += row["status"] != "passed";
  std::printf(
      "unimouse batch collect: %zu jobs, %zu passed, %d not passed\n  report: %s (also "
      "results.csv, results.json, summary.csv, junit.xml)\n",
      rows.size(), rows.size() - static_cast<size_t>(not_passed), not_passed,
      (fs::path(out) / "report.html").c_str());
  return not_passed == 0 ? kExitPassed : kExitFailed;
}

int RunBatchJob(const std::string& manifest, const std::string& id, const std::string& out_dir,
                const std::string& program, const std::string& version) {
  const Manifest m = LoadManifest(manifest);
  return RunJob(m, FindJob(m, id), out_dir, program, version);
}

}  // namespace unimouse::batch
