// SPDX-License-Identifier: GPL-3.0-or-later
#include "job_runner.h"

#include <fcntl.h>
#include <signal.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include "install_paths.h"
#include "sha256.h"
#include "text_file.h"
#include "transport_spec.h"
#include "unimouse/errors.h"

namespace unimouse::batch {
namespace {

namespace fs = std::filesystem;

volatile std::sig_atomic_t stop_signal = 0;

void OnStop(int signal) { stop_signal = signal; }

std::string Seconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", seconds);
  return text;
}

// the program's full path from PATH, or ""
std::string FindProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string list = path != nullptr ? path : "/usr/bin:/bin";
  for (size_t at = 0; at <= list.size();) {
    const size_t end = std::min(list.find(':', at), list.size());
    const fs::path candidate = fs::path(list.substr(at, end - at)) / name;
    if (end > at && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    at = end + 1;
  }
  return "";
}

// the run's environment is this one; only the limits and the file system differ
[[noreturn]] void LimitAndExec(const ExecArgs& args, const JobLimits& limits,
                               const std::string& log_file) {
  const auto limit = [](int resource, rlim_t soft, rlim_t hard) {
    const rlimit r{soft, hard};
    ::setrlimit(resource, &r);
  };
  const rlim_t mb = rlim_t{1} << 20;
  limit(RLIMIT_AS, static_cast<rlim_t>(limits.memory_mb) * mb,
        static_cast<rlim_t>(limits.memory_mb) * mb);
  limit(RLIMIT_FSIZE, static_cast<rlim_t>(limits.file_size_mb) * mb,
        static_cast<rlim_t>(limits.file_size_mb) * mb);
  // SIGXCPU at the limit, SIGKILL a little later for a program that ignores it
  const rlim_t cpu_s = static_cast<rlim_t>(std::ceil(limits.cpu_time_s));
  limit(RLIMIT_CPU, cpu_s, cpu_s + 5);
  limit(RLIMIT_CORE, 0, 0);
  const int log = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log < 0) ::_exit(kExitRuntimeFault);
  ExecInOwnGroup(args, log, log);
}

}  // namespace

ExecArgs::ExecArgs(const std::vector<std::string>& argv) : strings(argv) {
  for (auto& s : strings) pointers.push_back(s.data());
  pointers.push_back(nullptr);
}

void ExecInOwnGroup(const ExecArgs& args, int out_fd, int err_fd) {
  ::setpgid(0, 0);
  const int null = ::open("/dev/null", O_RDWR | O_CLOEXEC);
  if (null >= 0) ::dup2(null, 0);
  ::dup2(out_fd >= 0 ? out_fd : null, 1);
  ::dup2(err_fd >= 0 ? err_fd : null, 2);
  // what this process changed for itself goes back to what a program expects
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  ::execv(args.pointers[0], args.pointers.data());
  ::_exit(127);
}

namespace {

// this process is the subreaper of the run: whatever the run started and left behind comes
// here when its parent ends, and is ended too
void EndOrphans() {
  const pid_t self = ::getpid();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (std::chrono::steady_clock::now() < deadline) {
    bool found = false;
    for (const auto& entry :
         fs::directory_iterator("/proc", fs::directory_options::skip_permission_denied)) {
      const std::string name = entry.path().filename().string();
      if (name.find_first_not_of("0123456789") != std::string::npos) continue;
      std::ifstream stat(entry.path() / "stat");
      std::string text;
      std::getline(stat, text);
      // "pid (comm) state ppid ...": the name may hold spaces and parentheses
      const size_t close = text.rfind(')');
      if (close == std::string::npos) continue;
      char state = 0;
      int ppid = 0;
      if (std::sscanf(text.c_str() + close + 1, " %c %d", &state, &ppid) == 2 && ppid == self) {
        found = true;
        ::kill(std::atoi(name.c_str()), SIGKILL);
      }
    }
    while (::waitpid(-1, nullptr, WNOHANG) > 0) {
    }
    if (!found) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

nlohmann::json ReadResult(const fs::path& file) {
  try {
    if (PathExists(file)) return nlohmann::json::parse(ReadTextFile(file.string()));
  } catch (const std::exception&) {
    // a half-written or garbled file is no result
  }
  return nullptr;
}

template <typename T>
T Get(const nlohmann::json& j, const nlohmann::json::json_pointer& at, T fallback) {
  try {
    if (j.is_object() && j.contains(at)) return j.at(at).get<T>();
  } catch (const std::exception&) {
  }
  return fallback;
}

bool IsMmsResult(const nlohmann::json& result) {
  return Get<std::string>(result, nlohmann::json::json_pointer("/command"), "") == "mms";
}

// what a job scores: the scenario's scores, or an mms run's score and counts
nlohmann::json Scores(const nlohmann::json& result) {
  using P = nlohmann::json::json_pointer;
  if (!IsMmsResult(result)) {
    return Get<nlohmann::json>(result, P("/scenario/scores"), nlohmann::json::object());
  }
  nlohmann::json scores = nlohmann::json::object();
  for (const char* name : {"score", "moves", "crashes"}) {
    if (result.contains(name)) scores[name] = result[name];
  }
  return scores;
}

nlohmann::json LimitsJson(const JobLimits& l) {
  return {{"wall_time_s", l.wall_time_s},
          {"cpu_time_s", l.cpu_time_s},
          {"memory_mb", l.memory_mb},
          {"file_size_mb", l.file_size_mb},
          {"sandbox", l.sandbox}};
}

}  // namespace

std::string SignalName(int signal) {
  const char* abbrev = ::sigabbrev_np(signal);
  return abbrev != nullptr ? std::string("SIG") + abbrev : "signal " + std::to_string(signal);
}

JobOutcome ClassifyJob(const ProcessEnd& end, const nlohmann::json& result,
                       const JobLimits& limits) {
  using P = nlohmann::json::json_pointer;
  if (end.timed_out) {
    return {"timeout",
            "still running after the wall-time limit of " + Seconds(limits.wall_time_s) + " s"};
  }
  if (end.signal != 0) {
    std::string why = "killed by " + SignalName(end.signal);
    if (end.signal == SIGXCPU || end.signal == SIGKILL) {
      why += " (the CPU time limit is " + Seconds(limits.cpu_time_s) + " s, memory " +
             std::to_string(limits.memory_mb) + " MB)";
    }
    if (end.signal == SIGXFSZ) {
      why += " (wrote past the file size limit of " + std::to_string(limits.file_size_mb) + " MB)";
    }
    return {"crashed", why};
  }
  // an mms program's run says why it ended in its own field (docs/mms.md)
  const bool mms = IsMmsResult(result);
  const std::string error = Get<std::string>(result, P(mms ? "/reason" : "/error"), "");
  const std::string reason = Get<std::string>(result, P(mms ? "/reason" : "/scenario/reason"), "");
  if (result.is_null()) {
    return {"crashed", "the run ended with exit code " + std::to_string(end.exit_code) +
                           " and wrote no result.json"};
  }
  switch (end.exit_code) {
    case kExitPassed:
      return {"passed", reason};
    case kExitFailed:
      return {"failed", reason};
    case kExitBadInput:
      return {"bad_input", error};
    case kExitRuntimeFault: {
      if (mms) {
        // the program killed by a signal, or the run stopped by one from outside the batch
        const std::string status = Get<std::string>(result, P("/status"), "");
        const bool crashed = status == "program_crashed" || status == "interrupted";
        return {crashed ? "crashed" : "firmware_error", reason};
      }
      // a firmware ended by a fatal signal is named by the link ("the firmware crashed: SIGSEGV");
      // a run stopped by a signal from outside the batch ("interrupted by SIGTERM") ended by it
      if (error.find("firmware crashed: SIG") != std::string::npos ||
          Get<std::string>(result, P("/status"), "") == "interrupted") {
        return {"crashed", error};
      }
      // a component's failure is the firmware's (its link) or the robot's; else the script's
      if (error.find("component '") != std::string::npos) return {"firmware_error", error};
      return {"script_error", error.empty() ? reason : error};
    }
    default:
      return {"crashed", "the run ended with exit code " + std::to_string(end.exit_code)};
  }
}

std::string JobDirectory(const std::string& batch_out, const Job& job) {
  return (fs::path(batch_out) / "jobs" / job.id).string();
}

nlohmann::json JobInputs(const Manifest& manifest, const Job& job) {
  nlohmann::json inputs = nlohmann::json::array();
  auto add = [&](const char* role, const std::string& file) {
    // a file that cannot be read is the run's bad input; here it is only named
    std::string sha256;
    try {
      sha256 = FileSha256(file);
    } catch (const InputError&) {
    }
    inputs.push_back({{"role", role}, {"file", file}, {"sha256", sha256}});
  };
  // a bundled name stands for its file; a name that is none is the run's bad input
  auto bundled = [&](const char* role, const std::string& name, const char* folder,
                     const char* extension) {
    try {
      add(role, ResolveDataFile(name, folder, extension));
    } catch (const InputError&) {
      inputs.push_back({{"role", role}, {"file", name}, {"sha256", ""}});
    }
  };
  std::vector<int> submissions = {job.submission};
  submissions.insert(submissions.end(), job.rivals.begin(), job.rivals.end());
  for (const int index : submissions) {
    const Submission& sub = manifest.submissions[static_cast<size_t>(index)];
    if (!sub.controller.empty()) add("submission", sub.controller);
    if (!sub.link.empty()) {
      const std::string firmware = link::ParseTransportSpec(sub.link).firmware;
      if (!firmware.empty()) add("submission", firmware);
    }
    // an mms program: each of its words that names a file (the program, its script)
    for (const std::string& word : sub.mms) {
      const fs::path file = fs::path(sub.program_dir) / word;
      std::error_code error;
      if (fs::is_regular_file(file, error)) add("submission", file.lexically_normal().string());
    }
  }
  if (job.scenario >= 0) {
    const ScenarioEntry& scenario = manifest.scenarios[static_cast<size_t>(job.scenario)];
    bundled("scenario", scenario.file, "scenarios/", ".lua");
    for (const int index : submissions) {
      const Submission& sub = manifest.submissions[static_cast<size_t>(index)];
      bundled("robot", sub.robot.empty() ? manifest.robot : sub.robot, "robots/", ".yaml");
    }
    const std::string maze = !job.maze_file.empty() ? job.maze_file
                             : scenario.has_maze    ? scenario.default_maze
                                                    : std::string();
    if (!maze.empty()) bundled("maze", maze, "mazes/", ".txt");
  } else if (!job.maze_file.empty()) {
    bundled("maze", job.maze_file, "mazes/", ".txt");
  }
  return inputs;
}

nlohmann::json JobCommand(const Manifest& manifest, const Job& job, const std::string& batch_out) {
  const Submission& sub = manifest.submissions[static_cast<size_t>(job.submission)];
  return {{"run", RunArguments(manifest, job, JobDirectory(batch_out, job))},
          {"limits", LimitsJson(sub.limits)},
          {"inputs", JobInputs(manifest, job)}};
}

bool JobIsDone(const Manifest& manifest, const Job& job, const std::string& batch_out) {
  const nlohmann::json record = ReadResult(fs::path(JobDirectory(batch_out, job)) / "job.json");
  return record.is_object() && record.contains("command") &&
         record["command"] == JobCommand(manifest, job, batch_out);
}

namespace {

// what the job's wait for one of its processes saw
struct Waited {
  ProcessEnd end;
  bool interrupted = false;  // SIGINT or SIGTERM came: the process was stopped
  double wall_s = 0;
};

// the argv in front of a program that runs it in bubblewrap: the file system read-only but for
// the job's directory, no network, its own process ids (everything in it ends with it)
std::vector<std::string> SandboxArgv(const std::string& bwrap, const fs::path& dir) {
  if (bwrap.empty()) return {};
  return {bwrap,
          "--ro-bind",
          "/",
          "/",
          "--dev",
          "/dev",
          "--dev-bind-try",
          "/dev/dri",
          "/dev/dri",
          "--proc",
          "/proc",
          "--bind",
          dir.string(),
          dir.string(),
          "--unshare-net",
          "--unshare-pid",
          "--unshare-ipc",
          "--die-with-parent",
          "--new-session",
          "--"};
}

// runs argv in a process group of its own under the limits, its output into log_file, killed at
// wall_time_s; whatever it left behind is ended before this returns
Waited RunLimited(const std::vector<std::string>& argv, const JobLimits& limits, double wall_time_s,
                  const std::string& log_file, bool sandboxed, const std::string& job_id) {
  const auto start = std::chrono::steady_clock::now();
  const ExecArgs args(argv);
  const pid_t child = ::fork();
  UNIMOUSE_THROW_UNLESS(child >= 0, "cannot start a process for job " + job_id);
  if (child == 0) LimitAndExec(args, limits, log_file);
  ::setpgid(child, child);

  Waited waited;
  ProcessEnd& end = waited.end;
  int status = 0;
  const auto limit = std::chrono::duration<double>(wall_time_s);
  std::optional<std::chrono::steady_clock::time_point> asked;  // when a stop was asked for
  while (::waitpid(child, &status, WNOHANG) == 0) {
    const auto now = std::chrono::steady_clock::now();
    if (!end.timed_out && now - start > limit) {
      end.timed_out = true;
      ::kill(-child, SIGKILL);
    }
    if (stop_signal != 0 && !asked) {
      // the run ends as at Ctrl-C, and for good two seconds later
      asked = now;
      ::kill(-child, SIGTERM);
    }
    if (asked && now - *asked > std::chrono::seconds(2)) ::kill(-child, SIGKILL);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  waited.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ::kill(-child, SIGKILL);
  EndOrphans();
  waited.interrupted = asked.has_value();

  if (WIFSIGNALED(status)) end.signal = WTERMSIG(status);
  if (WIFEXITED(status)) end.exit_code = WEXITSTATUS(status);
  // bubblewrap reports its program's fatal signal N as exit code 128 + N
  if (sandboxed && end.exit_code > 128 && end.exit_code < 128 + NSIG) {
    end.signal = end.exit_code - 128;
    end.exit_code = -1;
  }
  return waited;
}

// why bubblewrap cannot run a program in the job's sandbox here (its own first line of
// complaint), or "" when it can
std::string SandboxProblem(const std::string& bwrap, const fs::path& dir,
                           const std::string& job_id) {
  std::vector<std::string> argv = SandboxArgv(bwrap, dir);
  argv.push_back(FindProgram("true"));
  const fs::path log = dir / "sandbox.log";
  const Waited probe = RunLimited(argv, JobLimits{}, 10, log.string(), true, job_id);
  std::string problem;
  if (probe.end.exit_code != 0 || probe.end.signal != 0 || probe.end.timed_out) {
    std::istringstream text(ReadTextFile(log.string()));
    std::getline(text, problem);
    if (problem.empty()) problem = "it ended with exit code " + std::to_string(probe.end.exit_code);
  }
  fs::remove(log);
  return problem;
}

// why a replay wrote no page, or "" when it wrote one
std::string ReplayFailure(const Waited& replay, double wall_time_s) {
  const ProcessEnd& end = replay.end;
  if (end.timed_out) {
    return "still running after the replay's wall-time limit of " + Seconds(wall_time_s) + " s";
  }
  if (end.signal != 0) return "killed by " + SignalName(end.signal);
  if (end.exit_code != kExitPassed) {
    return "ended with exit code " + std::to_string(end.exit_code) + " (see replay.log)";
  }
  return "";
}

}  // namespace

int RunJob(const Manifest& manifest, const Job& job, const std::string& batch_out,
           const std::string& program, const std::string& version) {
  const Submission& sub = manifest.submissions[static_cast<size_t>(job.submission)];
  const JobLimits& limits = sub.limits;
  const fs::path dir = fs::absolute(JobDirectory(batch_out, job));
  fs::create_directories(dir);
  // an earlier run's files would pass for this one's
  for (const char* file : {"job.json", "result.json", "run.mcap", kReplayPage, "replay.log"}) {
    fs::remove(dir / file);
  }

  std::string bwrap = limits.sandbox == "none" ? "" : FindProgram("bwrap");
  UNIMOUSE_THROW_UNLESS(
      limits.sandbox != "bwrap" || !bwrap.empty(),
      "submission '" + sub.name + "': sandbox: bwrap, but bwrap is not installed");
  // installed is not enough: in a chroot or a container without the right to mount, bubblewrap
  // cannot make its sandbox, and every job would fail as if its submission had
  const std::string sandbox_problem = bwrap.empty() ? "" : SandboxProblem(bwrap, dir, job.id);
  UNIMOUSE_THROW_UNLESS(
      limits.sandbox != "bwrap" || sandbox_problem.empty(),
      "submission '" + sub.name +
          "': sandbox: bwrap, but bwrap cannot make its sandbox here: " + sandbox_problem);
  if (!sandbox_problem.empty()) bwrap.clear();
  const std::vector<std::string> sandbox = SandboxArgv(bwrap, dir);
  std::vector<std::string> argv = sandbox;
  argv.push_back(program);
  const nlohmann::json command = JobCommand(manifest, job, batch_out);
  for (const auto& a : command["run"]) argv.push_back(a.get<std::string>());

  struct sigaction action = {};
  action.sa_handler = OnStop;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  const Waited run = RunLimited(argv, limits, limits.wall_time_s, (dir / "run.log").string(),
                                !bwrap.empty(), job.id);
  if (run.interrupted) return kExitRuntimeFault;
  const ProcessEnd& end = run.end;
  const double wall_s = run.wall_s;

  // the run's page, from its recording however the run ended, by the same program in the same
  // sandbox and limits; its failure is only noted, never the job's
  nlohmann::json replay_page = nullptr, replay_error = nullptr;
  if (PathExists(dir / "run.mcap")) {
    const double replay_limit_s = std::min(limits.wall_time_s, kReplayWallTime_s);
    std::vector<std::string> replay = sandbox;
    for (const std::string& a : {program, std::string("replay"), dir.string(),
                                 std::string("--html"), (dir / kReplayPage).string()}) {
      replay.push_back(a);
    }
    const Waited made = RunLimited(replay, limits, replay_limit_s, (dir / "replay.log").string(),
                                   !bwrap.empty(), job.id);
    if (made.interrupted) return kExitRuntimeFault;
    const std::string failure = ReplayFailure(made, replay_limit_s);
    if (failure.empty() && PathExists(dir / kReplayPage)) {
      replay_page = kReplayPage;
    } else {
      fs::remove(dir / kReplayPage);
      replay_error = failure.empty() ? "wrote no page (see replay.log)" : failure;
    }
  }

  const nlohmann::json result = ReadResult(dir / "result.json");
  JobOutcome outcome = ClassifyJob(end, result, limits);
  // the manifest's paths are made absolute for the run; the teacher wrote them relative to it
  const std::string beside = fs::path(manifest.file).parent_path().string() + "/";
  for (size_t at; (at = outcome.reason.find(beside)) != std::string::npos;) {
    outcome.reason.erase(at, beside.size());
  }
  using P = nlohmann::json::json_pointer;
  nlohmann::json record = {
      {"id", job.id},
      {"submission", SubmissionsName(manifest, job)},
      {"scenario", ScenarioName(manifest, job)},
      {"maze", job.maze.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.maze)},
      {"seed", job.seed},
      {"status", outcome.status},
      {"reason", outcome.reason},
      {"exit_code", end.exit_code >= 0 ? nlohmann::json(end.exit_code) : nlohmann::json(nullptr)},
      {"signal",
       end.signal != 0 ? nlohmann::json(SignalName(end.signal)) : nlohmann::json(nullptr)},
      {"scores", Scores(result)},
      {"sim_time_s",
       Get<nlohmann::json>(result, P(IsMmsResult(result) ? "/contest_time_s" : "/sim_time_s"),
                           nullptr)},
      {"wall_time_s", wall_s},
      {"replay_page", replay_page},
      {"replay_error", replay_error},
      {"sandbox", bwrap.empty() ? "none" : "bwrap"},
      {"sandbox_problem",
       sandbox_problem.empty() ? nlohmann::json(nullptr) : nlohmann::json(sandbox_problem)},
      {"manifest", manifest.file},
      {"unimouse_version", version},
      {"command", command}};
  // written whole: a reader never sees half of it
  WriteTextFile((dir / "job.json").string(),
                record.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return outcome.status == "passed" ? kExitPassed : kExitFailed;
}

}  // namespace unimouse::batch
