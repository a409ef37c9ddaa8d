// SPDX-License-Identifier: GPL-3.0-or-later
#include "mms_run.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <thread>

#include "geom_extent.h"
#include "install_paths.h"
#include "mms_physical.h"
#include "mms_picture.h"
#include "result_record.h"
#include "transport.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr size_t kMaxLineBytes = 4096;
constexpr int kMaxLoggedInvalid = 20;

// how a run ended, in result.json's words
struct Ending {
  std::string status;
  std::string reason;
  int exit_code = kExitFailed;
};

// a line as the log shows it: printable, short
std::string Printable(const std::string& line) {
  std::string shown;
  for (const unsigned char c : line.substr(0, 80)) {
    if (c >= 32 && c < 127) {
      shown += char(c);
    } else {
      char hex[8];
      std::snprintf(hex, sizeof(hex), "\\x%02x", c);
      shown += hex;
    }
  }
  return line.size() > 80 ? shown + "..." : shown;
}

// where the command lines come from and the replies go
class Channel {
 public:
  virtual ~Channel() = default;
  /// Appends what arrived within `timeout` to `out`; false when the other side is gone for good.
  virtual bool Read(std::string& out, std::chrono::milliseconds timeout) = 0;
  /// Writes what the other side takes now and erases it from `pending`.
  virtual void Write(std::string& pending) = 0;
  /// Returns how long the first command line may take to come.
  virtual Clock::duration first_wait(Clock::duration reply_timeout) const { return reply_timeout; }
  /// Returns how the run ends when Read says the other side is gone.
  virtual Ending Gone(bool goal_reached, double reply_timeout_s) = 0;
};

// the program, in its own process group so that whatever it starts goes with it
class Child final : public Channel {
 public:
  Child(const std::vector<std::string>& program, const std::string& dir) {
    int to_child[2], from_child[2], exec_error[2];
    if (pipe(to_child) != 0 || pipe(from_child) != 0 || pipe2(exec_error, O_CLOEXEC) != 0) {
      throw RuntimeFault(std::string("cannot make pipes: ") + std::strerror(errno));
    }
    // made before fork(): the child allocates nothing
    std::vector<char*> argv;
    for (const std::string& arg : program) argv.push_back(const_cast<char*>(arg.c_str()));
    argv.push_back(nullptr);
    pid_ = fork();
    if (pid_ < 0) throw RuntimeFault(std::string("cannot fork: ") + std::strerror(errno));
    if (pid_ == 0) {
      setpgid(0, 0);
      dup2(to_child[0], 0);
      dup2(from_child[1], 1);
      for (int fd : {to_child[0], to_child[1], from_child[0], from_child[1], exec_error[0]}) {
        close(fd);
      }
      signal(SIGPIPE, SIG_DFL);
      if (!dir.empty() && chdir(dir.c_str()) != 0) {
        const int error = errno;
        (void)!write(exec_error[1], &error, sizeof(error));
        _exit(127);
      }
      execvp(argv[0], argv.data());
      const int error = errno;
      (void)!write(exec_error[1], &error, sizeof(error));
      _exit(127);
    }
    setpgid(pid_, pid_);
    close(to_child[0]);
    close(from_child[1]);
    close(exec_error[1]);
    in_ = to_child[1];
    out_ = from_child[0];

    // the exec-error pipe closes unread when exec succeeds
    int error = 0;
    const ssize_t n = read(exec_error[0], &error, sizeof(error));
    close(exec_error[0]);
    if (n == sizeof(error)) {
      Stop();
      throw InputError("cannot run '" + program[0] + "'" + (dir.empty() ? "" : " in " + dir) +
                       ": " + std::strerror(error));
    }
    fcntl(in_, F_SETFL, fcntl(in_, F_GETFL) | O_NONBLOCK);
    fcntl(out_, F_SETFL, fcntl(out_, F_GETFL) | O_NONBLOCK);
  }
  ~Child() override { Stop(); }

  bool Read(std::string& out, std::chrono::milliseconds timeout) override {
    pollfd readable = {out_, POLLIN, 0};
    if (poll(&readable, 1, int(timeout.count())) < 0 && errno != EINTR) {
      throw RuntimeFault(std::string("poll: ") + std::strerror(errno));
    }
    if ((readable.revents & (POLLIN | POLLHUP | POLLERR)) == 0) return true;
    char buffer[65536];
    const ssize_t n = read(out_, buffer, sizeof(buffer));
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return true;
    if (n <= 0) return false;
    out.append(buffer, size_t(n));
    return true;
  }

  void Write(std::string& pending) override {
    while (!pending.empty() && in_ >= 0) {
      const ssize_t n = write(in_, pending.data(), pending.size());
      if (n > 0) {
        pending.erase(0, size_t(n));
        continue;
      }
      // a program that closed its stdin no longer hears replies
      if (n < 0 && errno != EAGAIN && errno != EINTR) pending.clear();
      return;
    }
  }

  Ending Gone(bool goal_reached, double reply_timeout_s) override {
    const int status = WaitExit(std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(reply_timeout_s)));
    if (status != -1 && WIFSIGNALED(status)) {
      return {"program_crashed",
              std::string("the program was killed by signal ") + strsignal(WTERMSIG(status)),
              kExitRuntimeFault};
    }
    if (goal_reached) return {"goal_reached", "the program ended after the goal", kExitPassed};
    const std::string how = status == -1
                                ? "closed its stdout"
                                : "exited with code " + std::to_string(WEXITSTATUS(status));
    return {"program_exited", "the program " + how + " before the mouse reached the goal",
            kExitRuntimeFault};
  }

  /// Waits up to `timeout` for the program to exit by itself; returns its wait status or -1.
  int WaitExit(Clock::duration timeout) {
    const Clock::time_point deadline = Clock::now() + timeout;
    while (pid_ > 0) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return status;
      }
      if (Clock::now() > deadline) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return -1;
  }

  /// Kills the program and its process group, and reaps it.
  void Stop() {
    if (in_ >= 0) close(in_);
    if (out_ >= 0) close(out_);
    in_ = out_ = -1;
    if (pid_ > 0) {
      kill(-pid_, SIGKILL);
      int status = 0;
      waitpid(pid_, &status, 0);
      pid_ = -1;
    }
  }

 private:
  pid_t pid_ = -1;
  int in_ = -1;
  int out_ = -1;
};

// a board or relay on a pty, serial port or TCP connection, through the link's transports: it may
// come and go (a board resets when its port opens), so only its silence ends the run
class Device final : public Channel {
 public:
  Device(const std::string& spec, double connect_timeout_s)
      : connect_timeout_(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(connect_timeout_s))) {
    // a board or relay at the end of a port: not a firmware the simulator runs, nor a scheme
    // it does not know
    const link::TransportKind* kind = nullptr;
    try {
      kind = link::ParseTransportSpec(spec).kind;
    } catch (const InputError&) {
    }
    if (kind == nullptr || kind->firmware != link::FirmwareHost::kBoard) {
      throw InputError("--port " + spec + ": " + link::TransportUsages(/*boards_only=*/true));
    }
    transport_ = link::OpenTransport(spec);
    std::fprintf(stderr, "mms: waiting for the program on the %s\n",
                 transport_->Describe().c_str());
  }

  bool Read(std::string& out, std::chrono::milliseconds timeout) override {
    transport_->WaitReadable(timeout);
    if (!transport_->Connected()) {
      // no peer yet, or it went away: Read tries to get one back
      std::this_thread::sleep_for(std::min(timeout, std::chrono::milliseconds(20)));
    }
    std::vector<uint8_t> bytes;
    transport_->Read(bytes, 65536);
    out.append(bytes.begin(), bytes.end());
    return true;
  }

  void Write(std::string& pending) override {
    const size_t n = transport_->Write(
        std::span(reinterpret_cast<const uint8_t*>(pending.data()), pending.size()));
    pending.erase(0, n);
  }

  Clock::duration first_wait(Clock::duration) const override { return connect_timeout_; }

  Ending Gone(bool, double) override { return {"error", "the device closed", kExitRuntimeFault}; }

 private:
  std::unique_ptr<link::Transport> transport_;
  Clock::duration connect_timeout_;
};

// the protocol session: reads command lines, answers them, decides when the run ends
class Exchange {
 public:
  /// `session`: the physics tier's run, which draws what the program displays; or nullptr.
  Exchange(const MmsRunOptions& options, MmsWorld& world, Channel& channel, Session* session)
      : options_(options), world_(world), channel_(channel), session_(session) {}

  Ending Run() {
    const auto reply_timeout = std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(options_.reply_timeout_s));
    Clock::time_point deadline = Clock::now() + channel_.first_wait(reply_timeout);
    std::string partial;
    bool discarding = false;  // inside an over-long line
    for (;;) {
      if (const std::string why = InterruptedBySignal(); !why.empty()) {
        return {"interrupted", why, kExitRuntimeFault};
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
      if (left.count() < 0) {
        const std::string quiet =
            "the program sent no command line for " + MmsNumber(options_.reply_timeout_s) + " s";
        // an invalid command gets no reply: a program that waits for one waits for ever
        return {"program_hang",
                last_dropped_.empty() ? quiet + " (does it flush stdout after each command?)"
                                      : quiet + " after its invalid command " + last_dropped_ +
                                            ", which gets no reply (does it wait for one?)",
                kExitRuntimeFault};
      }
      channel_.Write(pending_);
      // replies still to go: back soon to write them
      const auto wait = pending_.empty() ? left + std::chrono::milliseconds(1)
                                         : std::min(left, std::chrono::milliseconds(5));
      std::string buffer;
      if (!channel_.Read(buffer, wait)) {
        return channel_.Gone(world_.goal_reached(), options_.reply_timeout_s);
      }
      const size_t n = buffer.size();
      for (size_t i = 0; i < n; ++i) {
        if (buffer[i] != '\n') {
          if (discarding) continue;
          partial += buffer[i];
          if (partial.size() > kMaxLineBytes) {
            LogInvalid(partial, "longer than 4096 bytes", ++commands_);
            last_dropped_ = "of more than 4096 bytes (line " + std::to_string(commands_) + ")";
            partial.clear();
            discarding = true;
          }
          continue;
        }
        if (discarding) {
          discarding = false;
          continue;
        }
        if (std::optional<Ending> ending = Command(partial)) return *ending;
        partial.clear();

        // after the command: a paced move's wait is not the program's time
        deadline = Clock::now() + reply_timeout;
      }
    }
  }

  long commands() const { return commands_; }
  long invalid() const { return invalid_; }

 private:
  void LogInvalid(const std::string& line, const std::string& problem, long number) {
    ++invalid_;
    if (invalid_ <= kMaxLoggedInvalid) {
      std::fprintf(stderr, "mms: line %ld: invalid command '%s' dropped: %s\n", number,
                   Printable(line).c_str(), problem.c_str());
    } else if (invalid_ == kMaxLoggedInvalid + 1) {
      std::fprintf(stderr, "mms: more invalid commands are dropped without a line each\n");
    }
  }

  // carries out one line; returns how the run ends if it does
  std::optional<Ending> Command(const std::string& line) {
    // mms-arduino's convention: a board has one line for commands and its log, and a line
    // starting "log " is the log's
    if (line.rfind("log ", 0) == 0) {
      std::fprintf(stderr, "mms: log: %s\n", Printable(line.substr(4)).c_str());
      return std::nullopt;
    }
    if (++commands_ > options_.max_commands) {
      return Ending{"command_limit", "the program sent more than " +
                                         std::to_string(options_.max_commands) + " command lines"};
    }
    const MmsResponse response = world_.Handle(line);
    if (session_ != nullptr) session_->ShowDisplay(world_.Beliefs(), Hud());
    if (response.kind == MmsResponse::Kind::kInvalid) {
      LogInvalid(line, response.problem, commands_);
      last_dropped_ = "'" + Printable(line) + "' (line " + std::to_string(commands_) + ")";
      return std::nullopt;
    }
    last_dropped_.clear();
    if (!response.note.empty()) {
      std::fprintf(stderr, "mms: line %ld: %s\n", commands_, response.note.c_str());
    }
    if (const MmsMotion& failed = world_.body_failure(); !failed.failure.empty()) {
      return Ending{
          failed.failure,
          failed.why + " (line " + std::to_string(commands_) + ": " + Printable(line) + ")",
          failed.failure == "error" || failed.failure == "interrupted" ? kExitRuntimeFault
                                                                       : kExitFailed};
    }
    if (response.motion && options_.realtime) {
      std::this_thread::sleep_for(
          std::chrono::duration<double>(world_.contest_time_s() - paced_s_));
      paced_s_ = world_.contest_time_s();
    }
    if (response.kind == MmsResponse::Kind::kReply) {
      pending_ += response.reply + "\n";
      channel_.Write(pending_);
    }
    if (!response.motion) return std::nullopt;
    if (world_.contest_time_s() > options_.time_limit_s) {
      return world_.goal_reached()
                 ? Ending{"goal_reached", "the contest time ran out after the goal", kExitPassed}
                 : Ending{"time_out", "the contest time of " + MmsNumber(options_.time_limit_s) +
                                          " s ran out before the goal"};
    }
    if (response.crash && options_.end_on_crash) {
      return Ending{"crash", "the mouse ran into a wall (line " + std::to_string(commands_) + ": " +
                                 Printable(line) + ")"};
    }
    if (world_.goal_reached() && !options_.until_exit) {
      return Ending{"goal_reached", "the mouse reached the goal", kExitPassed};
    }
    return std::nullopt;
  }

  // what the pictures and the viewer show over the robot: the program, the moves, the clock
  std::vector<std::string> Hud() const {
    const std::string& program = options_.program.empty() ? options_.port : options_.program[0];
    char clock[64];
    std::snprintf(clock, sizeof(clock), "contest time %6.1f s%s", world_.contest_time_s(),
                  world_.goal_reached() ? "  goal reached" : "");
    return {
        "mms: " + fs::path(program).filename().string(),
        "moves " + std::to_string(world_.moves()) + "  crashes " + std::to_string(world_.crashes()),
        clock};
  }

  const MmsRunOptions& options_;
  MmsWorld& world_;
  Channel& channel_;
  Session* session_;
  std::string pending_;
  long commands_ = 0;
  long invalid_ = 0;
  std::string last_dropped_;  // the last line, when it was an invalid command
  double paced_s_ = 0;
};

// a robot wider than the maze's corridors scrapes both walls of every one: the physics tier
// cannot drive it, whatever the program does
void WarnIfTheRobotDoesNotFit(Session& session) {
  Kernel& kernel = session.kernel();
  const MazeDimensions maze = kernel.world().maze_dimensions();
  const double corridor_m = maze.cell_m - maze.wall_thickness_m;
  const double width_m = WidthAcrossX(kernel.mj_model(), kernel.state().data());
  if (width_m <= corridor_m) return;
  char text[256];
  std::snprintf(text, sizeof(text),
                "the robot is %.0f mm wide and this %s maze's corridors are %.0f mm: it does not "
                "fit (a half-size maze wants a half-size robot, --robot unimouse-half)",
                width_m * 1000, maze.cell_m < 0.1 ? "half-size" : "classic", corridor_m * 1000);
  kernel.Log(UNIMOUSE_LOG_WARNING, "mms", text);
}

void CheckOptions(const MmsRunOptions& o) {
  UNIMOUSE_THROW_UNLESS(!o.program.empty() || !o.port.empty(),
                        "unimouse mms: name the program after -- (unimouse mms --maze MAZE -- "
                        "./solver), or a board's --port");
  UNIMOUSE_THROW_UNLESS(o.program.empty() || o.port.empty(),
                        "unimouse mms: name the program after --, or a --port, not both");
  UNIMOUSE_THROW_UNLESS(o.physical || !o.true_walls, "--true-walls goes with --physical");
  UNIMOUSE_THROW_UNLESS(o.physical || !o.strict_contacts, "--strict-contacts goes with --physical");
  UNIMOUSE_THROW_UNLESS(
      o.maze_class == "auto" || o.maze_class == "classic" || o.maze_class == "half",
      "--maze-class " + o.maze_class + ": the classes are auto, classic and half");
  UNIMOUSE_THROW_UNLESS(o.physical || o.maze_class == "auto", "--maze-class goes with --physical");
  UNIMOUSE_THROW_UNLESS(o.physical || !o.watch, "--view goes with --physical");
  UNIMOUSE_THROW_UNLESS(!o.watch || !o.realtime, "--view paces the run itself: drop --realtime");
  auto positive = [](double v) { return std::isfinite(v) && v > 0; };
  auto non_negative = [](double v) { return std::isfinite(v) && v >= 0; };
  UNIMOUSE_THROW_UNLESS(positive(o.reply_timeout_s), "--reply-timeout-s must be positive");
  UNIMOUSE_THROW_UNLESS(positive(o.time_limit_s), "--time-limit-s must be positive");
  UNIMOUSE_THROW_UNLESS(positive(o.connect_timeout_s), "--connect-timeout-s must be positive");
  UNIMOUSE_THROW_UNLESS(non_negative(o.timing.cell_time_s), "--cell-time-s must be >= 0");
  UNIMOUSE_THROW_UNLESS(non_negative(o.timing.turn_time_s), "--turn-time-s must be >= 0");
  UNIMOUSE_THROW_UNLESS(o.max_commands > 0, "--max-commands must be positive");
}

}  // namespace

int RunMms(const MmsRunOptions& options) {
  nlohmann::json record = NewResultRecord("mms");
  record["mode"] = options.physical ? "mms-physical" : "mms-logic";
  record["program"] = options.program;
  if (!options.port.empty()) record["port"] = options.port;
  std::error_code ec;
  fs::remove(fs::path(options.out_dir) / "result.json", ec);
  Ending ending;
  try {
    CheckOptions(options);
    const std::string maze_file = ResolveDataFile(options.maze, "mazes/", ".txt");
    Maze maze = LoadMaze(maze_file);
    // mms's goal: the maze's centre cells, whatever the file marks
    if (options.centre_goal) maze.set_goals(CentreCells(maze.width(), maze.height()));
    SetMazeIdentity(record, IdentifyMaze(maze_file, maze));
    fs::create_directories(options.out_dir);
    signal(SIGPIPE, SIG_IGN);
    MmsWorld world(maze, options.timing);
    // the physics tier: the same maze in MuJoCo, the robot driven by the controller; the run
    // may take twice the contest time, so that the contest clock decides
    std::unique_ptr<Session> session;
    std::unique_ptr<MmsRobot> robot;
    if (options.physical) {
      SessionOptions run;
      run.robot = options.robot;
      run.maze = maze_file;
      run.duration_s = 2 * options.time_limit_s + 60;
      run.duration_given = true;
      run.seed = options.seed;
      run.out_dir = options.out_dir;
      if (options.maze_class != "auto") run.maze_class = options.maze_class;
      run.driven_by_caller = true;
      run.paced_by_caller = bool(options.watch);
      session = Session::Open(run);
      if (options.watch) session->SetStepWatcher(options.watch);
      WarnIfTheRobotDoesNotFit(*session);
      robot = std::make_unique<MmsRobot>(*session);
      world.SetBody(robot.get(), options.true_walls);
      world.set_contact_is_crash(options.strict_contacts);
    }
    std::unique_ptr<Channel> channel;
    if (options.port.empty()) {
      channel = std::make_unique<Child>(options.program, options.program_dir);
    } else {
      channel = std::make_unique<Device>(options.port, options.connect_timeout_s);
    }
    Exchange exchange(options, world, *channel, session.get());
    ending = exchange.Run();
    channel.reset();
    if (session && options.watch_end) {
      options.watch_end(*session, ending.status + ": " + ending.reason);
    }
    record["commands"] = exchange.commands();
    record["invalid_commands"] = exchange.invalid();
    record["goal_reached"] = world.goal_reached();
    record["moves"] = world.moves();
    record["crashes"] = world.crashes();
    record["contest_time_s"] = world.contest_time_s();
    record["stats"] = world.stats().ToJson();
    record["score"] = world.stats().Score();
    record["display"] = world.Display();
    if (session) {
      const MmsWallCounts& walls = world.wall_counts();
      record["physical"] = robot->Facts();
      record["physical"]["wall_readings"] = {{"sensed", walls.sensed},
                                             {"wrong", walls.wrong},
                                             {"from_the_maze", walls.unsensed},
                                             {"true_walls", options.true_walls}};
      // what the run's own record says of the robot and the simulation, with the keys and
      // shapes its result.json gives them
      const RunRecord run = session->Finish();
      const nlohmann::json run_json = RunRecordJson(run);
      for (const char* key : {"robot", "robot_sha256", "seed", "sim_time_s", "wall_time_s",
                              "real_time_factor", "robot_pose", "pictures", "warnings"}) {
        if (run_json.contains(key)) record["physical"][key] = run_json[key];
      }
      if (!run.error.empty()) record["physical"]["error"] = run.error;
    }
    if (!options.no_pictures) WriteMmsPictures(maze, world, options.out_dir);
  } catch (const InputError& e) {
    ending = {"error", e.what(), kExitBadInput};
  } catch (const std::exception& e) {
    ending = {"error", e.what(), kExitRuntimeFault};
  }
  record["status"] = ending.status;
  record["reason"] = ending.reason;
  record["exit_code"] = ending.exit_code;
  const std::string result = (fs::path(options.out_dir) / "result.json").string();
  try {
    WriteResultRecord(options.out_dir, record);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "unimouse: error: %s\n", e.what());
    return ending.exit_code == kExitPassed ? kExitRuntimeFault : ending.exit_code;
  }
  if (ending.status == "error") {
    std::fprintf(stderr, "unimouse: error: %s\n", ending.reason.c_str());
  } else {
    std::printf("mms: %s: %s; %s moves, score %g\n  result: %s\n", ending.status.c_str(),
                ending.reason.c_str(), record["moves"].dump().c_str(),
                record["score"].get<double>(), result.c_str());
  }
  return ending.exit_code;
}

}  // namespace unimouse
