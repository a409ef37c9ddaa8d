// SPDX-License-Identifier: GPL-3.0-or-later
#include "session.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <map>
#include <numbers>
#include <variant>

#include "console_progress.h"
#include "install_paths.h"
#include "maze_explorer.h"
#include "maze_plot.h"
#include "result_record.h"
#include "sha256.h"
#include "transport_spec.h"
#include "unimouse/errors.h"
#include "unimouse/plugin_abi.h"

namespace unimouse {
namespace {

namespace fs = std::filesystem;

// a scalar YAML node that says where it came from: a command-line option
YamlNode Scalar(const std::string& text, const std::string& option) {
  YamlNode node;
  node.kind = YamlNode::Kind::kScalar;
  node.scalar = text;
  node.location = {option, 0, 0};
  return node;
}

// seconds with the three decimals of a stopwatch
std::string Seconds3(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f", seconds);
  return text;
}

// the value a map of YAML scalars gives `key` last (a --link-set wins over --link), or ""
std::string LastScalar(const YamlNode& map, const std::string& key) {
  std::string value;
  for (const YamlEntry& entry : map.entries) {
    if (entry.first.scalar == key) value = entry.second.scalar;
  }
  return value;
}

// the default of a component type's string parameter, as its plugin declares it
std::string DefaultOf(const PluginRegistry& registry, const std::string& type,
                      const std::string& param) {
  const PluginRegistry::Entry* entry = registry.Find(type);
  for (int i = 0; entry != nullptr && i < entry->type->nparam; ++i) {
    const unimouse_param& p = entry->type->params[i];
    if (param == p.name && p.default_string != nullptr) return p.default_string;
  }
  return "";
}

// who drives the robot: a controller file, a firmware over a link (from --link or the robot
// file), both, or neither; each file the run started with its SHA-256
DriverRecord IdentifyDriver(const std::string& controller, const RobotSpec& robot,
                            const PluginRegistry& registry) {
  DriverRecord driver;
  if (!controller.empty()) driver.controller = IdentifyFile(controller);
  for (const ComponentSpec& c : robot.components) {
    if (c.type != "unimouse.link") continue;
    const std::string spec = LastScalar(c.params, "transport");
    const std::string profile = LastScalar(c.params, "profile");
    const link::TransportSpec parsed = link::ParseTransportSpec(spec);
    LinkRecord& link = driver.link.emplace();
    link.transport = parsed.kind->scheme;
    link.spec = spec;
    link.profile = profile.empty() ? DefaultOf(registry, c.type, "profile") : profile;
    // a board's firmware is not on this PC
    if (!parsed.firmware.empty()) link.firmware = IdentifyFile(parsed.firmware);
  }
  return driver;
}

// a start "X,Y,H" as a pose in the cell's centre; throws InputError naming `option`
Pose2D ParseStart(const std::string& text, const MazeDimensions& dims, const std::string& option) {
  int x = 0, y = 0;
  char heading = 0;
  int used = 0;
  const bool read = std::sscanf(text.c_str(), "%d,%d,%c%n", &x, &y, &heading, &used) == 3 &&
                    used == static_cast<int>(text.size());
  const std::string headings = "NESW";
  UNIMOUSE_THROW_UNLESS(read && headings.find(heading) != std::string::npos && x >= 0 && y >= 0,
                        option + " " + text +
                            ": write a cell and a heading, X,Y,H, e.g. 15,15,S (H one of N, E, "
                            "S, W)");
  const Heading h[] = {Heading::kNorth, Heading::kEast, Heading::kSouth, Heading::kWest};
  return CellCentre({x, y}, h[headings.find(heading)], dims);
}

// a robot's name as the result, sim.robots() and its folder use it
bool IsRobotName(const std::string& name) {
  return !name.empty() && name.size() <= 64 && name != "." && name != ".." &&
         name.find_first_not_of(
             "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") ==
             std::string::npos;
}

// a cell as the log and errors write it: "(x, y)"
std::string CellText(Cell c) {
  return "(" + std::to_string(c.x) + ", " + std::to_string(c.y) + ")";
}

// the cell a pose is in
std::string CellOf(const Pose2D& pose, const MazeDimensions& dims) {
  return CellText(CellAt(pose.x_m, pose.y_m, dims));
}

volatile std::sig_atomic_t interrupt_signal = 0;

void OnInterrupt(int signal) {
  // a second signal: the run did not reach a step boundary in time
  if (interrupt_signal != 0) ::_exit(kExitRuntimeFault);
  interrupt_signal = signal;
}

}  // namespace

ComponentSpec LinkComponent(const std::string& transport, const std::string& profile,
                            const std::vector<std::string>& sets) {
  ComponentSpec link;
  link.type = "unimouse.link";
  link.name = "link";
  link.location = {"--link " + transport, 0, 0};
  link.params.kind = YamlNode::Kind::kMap;
  link.params.location = link.location;
  const std::string option = link.location.file;
  link.params.entries.emplace_back(Scalar("transport", option), Scalar(transport, option));
  if (!profile.empty()) {
    const std::string where = "--firmware-profile " + profile;
    link.params.entries.emplace_back(Scalar("profile", where), Scalar(profile, where));
  }
  for (const std::string& set : sets) {
    const size_t eq = set.find('=');
    UNIMOUSE_THROW_UNLESS(eq != std::string::npos && eq > 0,
                          "--link-set " + set + ": write name=value");
    const std::string where = "--link-set " + set;
    link.params.entries.emplace_back(Scalar(set.substr(0, eq), where),
                                     Scalar(set.substr(eq + 1), where));
  }
  return link;
}

void InstallInterruptHandlers() {
  struct sigaction action = {};
  action.sa_handler = OnInterrupt;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int InterruptSignal() { return interrupt_signal; }

std::string InterruptedBySignal() {
  if (interrupt_signal == 0) return "";
  return std::string("interrupted by ") + (interrupt_signal == SIGINT ? "SIGINT" : "SIGTERM");
}

void WriteErrorResult(const SessionOptions& options, const std::string& error, int exit_code,
                      const std::string& traceback) {
  nlohmann::json record = NewResultRecord("run");
  record.update(
      {{"status", "error"}, {"error", error}, {"exit_code", exit_code}, {"seed", options.seed}});
  if (!traceback.empty()) record["traceback"] = traceback;
  try {
    WriteResultRecord(options.out_dir, record);
  } catch (const std::exception&) {
    // an output directory that cannot be written: the error itself is the one to report
  }
}

std::unique_ptr<Session> Session::Open(const SessionOptions& options) {
  std::unique_ptr<Session> session(new Session(options));
  std::error_code ec;
  fs::remove(fs::path(options.out_dir) / "result.json", ec);
  try {
    session->Assemble();
  } catch (const std::exception& e) {
    // a run that could not start says so where its result would be
    const bool bad_input = dynamic_cast<const InputError*>(&e) != nullptr;
    const auto* script = dynamic_cast<const ScriptFault*>(&e);
    WriteErrorResult(options, e.what(), bad_input ? kExitBadInput : kExitRuntimeFault,
                     script != nullptr ? script->traceback() : "");
    throw;
  }
  return session;
}

Session::Session(const SessionOptions& options) : options_(options) {}

Session::~Session() = default;

void Session::LoadRobots() {
  const SessionOptions& o = options_;
  std::vector<SessionRobot> given = o.robots;
  if (given.empty()) {
    given.push_back({o.robot, "", o.link, o.link_sets, o.firmware_profile, o.controller, o.start});
  }
  UNIMOUSE_THROW_UNLESS(
      given.size() <= static_cast<size_t>(kMaxRobots),
      std::to_string(given.size()) + " robots: a run has at most " + std::to_string(kMaxRobots));
  for (const SessionRobot& r : given) {
    Robot robot;
    robot.options = r;
    robot.file = ResolveDataFile(r.robot, "robots/", ".yaml");
    robot.sha256 = FileSha256(robot.file);
    robot.spec = LoadRobotSpec(robot.file);
    ApplyTraceOptions(o.trace, robot.spec);
    UNIMOUSE_THROW_UNLESS((r.link_sets.empty() && r.firmware_profile.empty()) || !r.link.empty(),
                          "--link-set and --firmware-profile go with --link");
    if (!r.link.empty()) {
      robot.spec.components.push_back(
          LinkComponent(link::ResolveBundledFirmware(r.link, FirmwareDirectory()),
                        r.firmware_profile, r.link_sets));
    }
    robot.name = r.name.empty() ? robot.spec.name : r.name;
    robots_.push_back(std::move(robot));
  }
  // several robots are told apart by name: a name given twice is a mistake, two robots of one
  // file are "unimouse" and "unimouse-2"
  const auto taken = [this](const std::string& name, size_t before) {
    for (size_t k = 0; k < before; ++k) {
      if (robots_[k].name == name) return true;
    }
    return false;
  };
  for (size_t i = 0; i < robots_.size() && robots_.size() > 1; ++i) {
    Robot& r = robots_[i];
    UNIMOUSE_THROW_UNLESS(
        IsRobotName(r.name),
        "robot name '" + r.name + "': use letters, digits, '_', '-' and '.' (give --name NAME)");
    if (!taken(r.name, i)) continue;
    UNIMOUSE_THROW_UNLESS(r.options.name.empty(),
                          "--name " + r.name + " is given to two robots; names must differ");
    const std::string base = r.name;
    for (int n = 2; taken(r.name, i); ++n) r.name = base + "-" + std::to_string(n);
  }
}

// where each robot starts: --start, else the scenario's place for it, else the maze's start;
// two robots in one cell is a mistake
void Session::PlaceRobots(ScenarioWorld& world) {
  const MazeDimensions dims = maze_ ? maze_->dimensions() : MazeDimensions{};
  for (size_t i = 0; i < robots_.size(); ++i) {
    Robot& r = robots_[i];
    if (!r.options.start.empty()) {
      r.start = ParseStart(r.options.start, dims, "--start");
      UNIMOUSE_THROW_UNLESS(
          !maze_ || maze_->Contains({static_cast<int>(r.start->x_m / dims.cell_m),
                                     static_cast<int>(r.start->y_m / dims.cell_m)}),
          "--start " + r.options.start + ": not a cell of the " + std::to_string(maze_->width()) +
              "x" + std::to_string(maze_->height()) + " maze");
    } else if (i == 0) {
      r.start = world.spawn;
    } else if (world.robot_spawns.contains(static_cast<int>(i))) {
      r.start = world.robot_spawns.at(static_cast<int>(i));
    }
  }
  if (robots_.size() < 2) return;
  Pose2D maze_start = {0, 0, std::numbers::pi / 2};
  if (maze_) maze_start = CellCentre(maze_->start(), maze_->start_heading(), dims);
  for (size_t i = 0; i < robots_.size(); ++i) {
    const std::string a = CellOf(robots_[i].start.value_or(maze_start), dims);
    for (size_t j = 0; j < i; ++j) {
      UNIMOUSE_THROW_UNLESS(a != CellOf(robots_[j].start.value_or(maze_start), dims),
                            "robots '" + robots_[j].name + "' and '" + robots_[i].name +
                                "' both start in cell " + a + ": give one of them --start X,Y,H");
    }
  }
}

void Session::Assemble() {
  const SessionOptions& o = options_;
  UNIMOUSE_THROW_UNLESS(o.duration_s > 0 && std::isfinite(o.duration_s),
                        "--duration must be a positive number of seconds");
  LoadRobots();
  std::vector<std::string> controllers;
  for (const Robot& r : robots_) controllers.push_back(r.options.controller);
  const bool any_controller = std::any_of(controllers.begin(), controllers.end(),
                                          [](const std::string& c) { return !c.empty(); });

  // a scenario builds its own world
  ScenarioWorld world;
  duration_s_ = o.duration_s;
  if (!o.scenario.empty()) {
    std::map<std::string, std::string> overrides = Scenario::ParseOverrides(o.sets);
    scenario_file_ = ResolveDataFile(o.scenario, "scenarios/", ".lua");
    // a script stuck in C for good: the process ends, and its result says why
    const auto on_hang = [this](const std::string& why) {
      WriteErrorResult(options_, why, kExitRuntimeFault, "");
    };
    scenario_ = Scenario::Load(scenario_file_, overrides, o.seed, on_hang);
    UNIMOUSE_THROW_UNLESS(static_cast<int>(robots_.size()) >= scenario_->min_robots(),
                          "scenario '" + scenario_->name() + "' needs at least " +
                              std::to_string(scenario_->min_robots()) +
                              " robots, and the run has " + std::to_string(robots_.size()) +
                              ": give --robot FILE once for each (docs/scenarios.md)");
    if (o.maze_given) {
      // a scenario's maze is its parameter `maze`: --maze sets it, as --set maze= would
      UNIMOUSE_THROW_UNLESS(scenario_->params().contains("maze"),
                            "--maze " + o.maze + ": scenario '" + scenario_->name() +
                                "' builds its own world and has no maze parameter");
      UNIMOUSE_THROW_UNLESS(!overrides.contains("maze") || overrides["maze"] == o.maze,
                            "--maze " + o.maze + " and --set maze=" + overrides["maze"] +
                                " name different mazes: give one");
      overrides["maze"] = o.maze;
      scenario_ = Scenario::Load(scenario_file_, overrides, o.seed, on_hang);
    }
    scenario_sha256_ = FileSha256(scenario_file_);
    scenario_->SetRobotNames(RobotNames());
    world = scenario_->BuildWorld();
    maze_ = std::move(world.maze);
    maze_file_ = world.maze_file;
    // a second beyond the limit lets the scenario give its own reason
    if (!o.duration_given && scenario_->time_limit_s() > 0) {
      duration_s_ = scenario_->time_limit_s() + 1;
    }
  } else {
    UNIMOUSE_THROW_UNLESS(o.sets.empty() && !any_controller,
                          "--set and --controller go with --scenario");
    if (o.maze != "none") {
      maze_file_ = ResolveDataFile(o.maze, "mazes/", ".txt");
      maze_ = std::make_unique<Maze>(LoadMaze(maze_file_));
      if (!o.maze_class.empty()) {
        maze_->set_class(o.maze_class == "half" ? MazeClass::kHalfSize : MazeClass::kClassic);
      }
    }
  }
  if (maze_ && !maze_file_.empty()) maze_record_ = IdentifyMaze(maze_file_, *maze_);
  PlaceRobots(world);
  UNIMOUSE_THROW_UNLESS(o.snapshot_on.empty() || scenario_,
                        "--snapshot-on watches a scenario's events: give --scenario");
  const PluginRegistry* registry = o.registry;
  if (registry == nullptr) {
    own_registry_.emplace();
    own_registry_->AddSearchPath(PluginSearchPath(o.plugin_path));
    registry = &*own_registry_;
  }

  // every message goes into the run's log, line by line, and to the console with its sim time
  fs::create_directories(o.out_dir);
  const std::string log_path = (fs::path(o.out_dir) / "log.txt").string();
  log_.reset(std::fopen(log_path.c_str(), "w"));
  UNIMOUSE_THROW_UNLESS(log_ != nullptr, log_path + ": cannot write the run's log");
  OpenRecording();
  KernelOptions kernel_options;
  kernel_options.seed = o.seed;
  kernel_options.output_dir = o.out_dir;
  kernel_options.boxes = std::move(world.boxes);
  kernel_options.spawn = robots_.front().start;
  kernel_options.log_sink = [this](double time_s, int level, const std::string& component,
                                   const std::string& message) {
    const char* kind = level == UNIMOUSE_LOG_ERROR     ? "error: "
                       : level == UNIMOUSE_LOG_WARNING ? "warning: "
                                                       : "";
    if (options_.console && (level != UNIMOUSE_LOG_DETAIL || options_.verbose)) {
      if (progress_) progress_->Clear();
      std::fprintf(stderr, "[%9.3f s] %s: %s%s\n", time_s, component.c_str(), kind,
                   message.c_str());
    }
    std::fprintf(log_.get(), "%.6f\t%s\t%s%s\n", time_s, component.c_str(), kind, message.c_str());
    if (level == UNIMOUSE_LOG_WARNING) warnings_.push_back(component + ": " + message);
    std::fflush(log_.get());
    Record([&](RunRecording& r) { r.Log(time_s, level, component, message); });
  };
  if (robots_.size() == 1) {
    kernel_ = Kernel::Create(robots_.front().spec, maze_.get(), *registry, kernel_options);
  } else {
    std::vector<KernelRobot> placed;
    for (const Robot& r : robots_) placed.push_back({r.spec, r.name, r.start});
    kernel_ = Kernel::Create(placed, maze_.get(), *registry, kernel_options);
  }
  // the maze picture shows what the first robot's firmware believes
  kernel_->AddReportListener([this](const std::string& component, int robot,
                                    const unimouse_report& report) {
    if (report.kind == UNIMOUSE_REPORT_MEASURE && report.name != nullptr) {
      measurements_[component][report.name] = report.value;
    } else if (report.kind == UNIMOUSE_REPORT_RESTART) {
      ++robots_[static_cast<size_t>(robot)].restarts;
    } else if (report.kind == UNIMOUSE_REPORT_VALUE && report.name != nullptr) {
      Robot& r = robots_[static_cast<size_t>(robot)];
      auto [at, added] = r.firmware_values.try_emplace(report.name, report.value);
      // NaN never equals itself: a NaN reported again is no change
      if (added ||
          !(at->second == report.value || (std::isnan(at->second) && std::isnan(report.value)))) {
        at->second = report.value;
        r.firmware_values_recorded = false;
      }
    } else {
      if (report.kind == UNIMOUSE_REPORT_VISITED) CheckReportedCell(robot, report.x, report.y);
      if (robot == 0 && beliefs_.Apply(report)) beliefs_recorded_ = false;
    }
  });
  if (scenario_) scenario_->Attach(*kernel_, controllers);
  for (size_t i = 0; i < robots_.size(); ++i) {
    robots_[i].driver = IdentifyDriver(controllers[i], robots_[i].spec, *registry);
  }
  // what drives the robot is what its components declared, wherever they came from (--link or
  // the robot file); said at once, so that a run meant to test something does not pass quietly
  // doing nothing
  const bool firmware = kernel_->declared(UNIMOUSE_TRAIT_FIRMWARE);
  if (!scenario_ && !firmware && !o.driven_by_caller) {
    kernel_->Log(UNIMOUSE_LOG_WARNING, "run",
                 "nothing drives the robot (no --scenario, --controller or --link): it stands "
                 "still; `unimouse run` with no options runs the contest with the bundled "
                 "firmware");
  } else if (any_controller && firmware) {
    kernel_->Log(UNIMOUSE_LOG_WARNING, "run",
                 "both --controller and a firmware link drive the robot: the firmware's "
                 "commands overwrite the controller's whenever they arrive");
  }

  // the pictures asked for; without any, final.png whenever the machine can draw
  if (o.pictures.Any() || o.only_asked_pictures) {
    pictures_ = std::make_unique<RunPictures>(*kernel_, o.pictures, &beliefs_, o.out_dir);
  } else {
    PictureOptions final_only = o.pictures;
    final_only.at_end = true;
    try {
      pictures_ = std::make_unique<RunPictures>(*kernel_, final_only, &beliefs_, o.out_dir);
    } catch (const RenderUnavailable& e) {
      no_pictures_ = e.what();
      pictures_ = std::make_unique<RunPictures>(*kernel_, o.pictures, &beliefs_, o.out_dir);
    }
  }
  pictures_->SetHudSource([this] { return hud(); });
  if (scenario_) {
    scenario_->SetPictureTaker(
        [this](const std::string& file, const std::string& camera, int width, int height) {
          return pictures_->Save(file, camera, width, height);
        });
    scenario_->SetOutputDirectory(o.out_dir);
    scenario_->SetEventSink([this](const ScenarioEvent& e) {
      Record([&](RunRecording& r) { r.Event(e.time_s, e.kind, e.robot, e.text, "{}"); });
    });
    for (const auto& kind : o.snapshot_on) {
      scenario_->SnapshotOn(kind, o.pictures.camera, o.pictures.width, o.pictures.height);
    }
  }

  steps_ = std::llround(duration_s_ / kernel_->timestep_s());
  // a board lives on the wall clock, from --link or the robot file alike; firmware in lock-step
  // sets the pace itself
  pace_ = !o.paced_by_caller && (o.realtime || kernel_->declared(UNIMOUSE_TRAIT_WALL_CLOCK));
  pacer_ = std::make_unique<RealTimePacer>(kernel_->timestep_s());
  if (o.progress && o.console) progress_ = std::make_unique<ConsoleProgress>(stderr);
  AttachInputs();
  RecordSample();
  start_ = std::chrono::steady_clock::now();
}

void Session::Step() {
  if (Over()) return;
  try {
    kernel_->Step();
    LogContacts();
    pictures_->AfterStep();
    RecordSample();
  } catch (const RuntimeFault& e) {
    fault_ = e.what();
    return;
  }
  if (watcher_) watcher_(*this);
  if (progress_) progress_->Update(kernel_->state().data().time, hud());
  // firmware in lock-step sets the pace itself, unless the wall clock was asked for to watch it
  if (pace_ && (options_.realtime || !kernel_->firmware_paced())) {
    pacer_->Wait(kernel_->state().step());
  }
}

std::vector<std::string> Session::RobotNames() const {
  std::vector<std::string> names;
  for (const Robot& r : robots_) names.push_back(r.name);
  return names;
}

// the moment a mouse gets lost: the first time the cell its firmware says it is in and the cell
// it is in differ by more than one (a report may come as the robot crosses into the next cell)
void Session::CheckReportedCell(int robot, int x, int y) {
  Robot& r = robots_[static_cast<size_t>(robot)];
  if (!maze_ || r.lost_reported) return;
  const Pose2D pose = kernel_->world().RobotPose(kernel_->state().data(), robot);
  const Cell at = CellAt(pose.x_m, pose.y_m, kernel_->world().maze_dimensions());
  if (std::max(std::abs(at.x - x), std::abs(at.y - y)) <= 1) return;
  r.lost_reported = true;
  const std::string text =
      (robots_.size() > 1 ? r.name + "'s " : std::string()) + "firmware reports cell " +
      CellText({x, y}) + " but the robot is in cell " + CellText(at) + ": it has lost its position";
  kernel_->Log(UNIMOUSE_LOG_WARNING, "run", text);
  const nlohmann::json data = {
      {"reported_cell", {x, y}}, {"true_cell", {at.x, at.y}}, {"x_m", pose.x_m}, {"y_m", pose.y_m}};
  Record([&](RunRecording& rec) {
    rec.Event(kernel_->state().data().time, "lost", r.name, text, data.dump());
  });
}

// each contact, as it begins, a line of the log and an event of the recording
void Session::LogContacts() {
  const std::vector<Contact>& contacts = kernel_->contacts().contacts();
  for (; logged_contacts_ < contacts.size(); ++logged_contacts_) {
    const Contact& c = contacts[logged_contacts_];
    std::string text = "contact: " + robots_[static_cast<size_t>(c.robot)].name + " touched ";
    if (c.other_robot >= 0) {
      text += "robot " + robots_[static_cast<size_t>(c.other_robot)].name;
    } else if (c.side == 'P') {
      text += "a post of cell " + CellText(*c.cell);
    } else if (c.side != 0) {
      text += "the " + std::string(1, c.side) + " wall of cell " + CellText(*c.cell);
    } else {
      text += "the scenery";
    }
    text += " with its " + c.part;
    kernel_->Log(UNIMOUSE_LOG_DETAIL, "run", text);
    Record([&](RunRecording& r) {
      r.Event(c.time_s, "contact", robots_[static_cast<size_t>(c.robot)].name,
              text.substr(sizeof("contact: ") - 1), ContactJson(c, RobotNames()).dump());
    });
  }
}

bool Session::Over() const {
  return !fault_.empty() || !stopped_.empty() || InterruptSignal() != 0 ||
         kernel_->state().step() >= steps_ || (scenario_ && scenario_->finished());
}

std::vector<std::string> Session::hud() const { return scenario_ ? scenario_->hud() : shown_hud_; }

void Session::ShowDisplay(FirmwareBeliefs beliefs, std::vector<std::string> hud) {
  beliefs_ = std::move(beliefs);
  beliefs_recorded_ = false;
  shown_hud_ = std::move(hud);
}

void Session::Stop(const std::string& why) {
  if (stopped_.empty()) stopped_ = why;
}

std::string Session::interruption() const {
  return stopped_.empty() ? InterruptedBySignal() : stopped_;
}

std::string Session::verdict() const {
  if (!fault_.empty()) return "error: " + fault_;
  if (!stopped_.empty()) return "interrupted: " + stopped_;
  if (InterruptSignal() != 0) return "interrupted";
  if (!scenario_) return "";
  const ScenarioOutcome& o = scenario_->outcome();
  return o.status + (o.reason.empty() ? "" : ": " + o.reason);
}

std::string Session::where() const {
  if (scenario_) return "in scenario " + scenario_->name();
  if (maze_) {
    return "in maze " + options_.maze + " (" + std::to_string(maze_->width()) + "x" +
           std::to_string(maze_->height()) + ")";
  }
  return "on an open floor";
}

// the maze as the firmware reported it on its debug channels: cells it knows (with their true
// walls dark), cells it visited, the walls it believes in, the path it last planned
void Session::DrawFirmwareMaze() {
  const Maze& maze = *maze_;
  WallKnowledge knowledge(maze);
  auto sense = [&](Cell c) {
    if (maze.Contains(c)) knowledge.Sense(maze, c);
  };
  for (const auto& [cell, walls] : beliefs_.walls) sense({cell.first, cell.second});
  for (const Cell& c : beliefs_.visited) sense(c);
  MazePicture picture;
  picture.maze = &maze;
  picture.knowledge = &knowledge;
  picture.beliefs = &beliefs_;
  picture.closed_path = DescribeRoute(beliefs_.path, maze.start_heading());
  const fs::path base = fs::path(options_.out_dir) / "maze";
  WriteMazePicture(picture, base.string() + ".png");
  WriteMazePicture(picture, base.string() + ".svg");
}

void Session::OpenRecording() {
  const RecordLevel level = ParseRecordLevel(options_.record);
  const std::string path = (fs::path(options_.out_dir) / "run.mcap").string();
  if (level == RecordLevel::kOff) {
    // never an earlier run's recording beside this run's result
    std::error_code ignored;
    fs::remove(path, ignored);
    return;
  }
  recording_ = std::make_unique<RunRecording>(path, level);
}

void Session::RecordSample() {
  if (!recording_) return;
  Record([&](RunRecording& r) {
    if (!r.Sample(*kernel_)) return;
    const double time_s = kernel_->state().data().time;
    if (!beliefs_recorded_) r.Beliefs(time_s, robots_.front().name, beliefs_);
    beliefs_recorded_ = true;
    if (std::vector<std::string> lines = hud(); lines != recorded_hud_) {
      r.Hud(time_s, lines);
      recorded_hud_ = std::move(lines);
    }
    for (Robot& robot : robots_) {
      if (!robot.firmware_values_recorded)
        r.FirmwareValues(time_s, robot.name, robot.firmware_values);
      robot.firmware_values_recorded = true;
    }
  });
}

// the files the run reads travel inside its recording from the start, so that even a recording
// cut short says what ran
void Session::AttachInputs() {
  Record([&](RunRecording& r) {
    // which attachment is which robot's file: robots of one file share its name
    std::map<std::string, std::string> files;
    for (size_t i = 0; i < robots_.size(); ++i) {
      const std::string name = fs::path(robots_[i].file).filename().string();
      files[std::to_string(i) + ".name"] = robots_[i].name;
      files[std::to_string(i) + ".file"] = name;
      if (i == 0 || name != fs::path(robots_[i - 1].file).filename().string()) {
        r.AttachFile(name, robots_[i].file, "application/yaml", 0);
      }
    }
    r.AddMetadata("unimouse.robots", files);
    if (!scenario_file_.empty()) {
      r.AttachFile(fs::path(scenario_file_).filename().string(), scenario_file_, "text/x-lua", 0);
    }
    if (!maze_file_.empty()) {
      r.AttachFile(fs::path(maze_file_).filename().string(), maze_file_, "text/plain", 0);
    }
  });
}

// a recording that cannot be written ends with a warning; the run goes on without it
void Session::Record(const std::function<void(RunRecording&)>& write) {
  if (!recording_) return;
  try {
    write(*recording_);
  } catch (const InputError& e) {
    recording_.reset();
    // said here, not through the kernel's log: this may be inside its log sink
    const std::string why = std::string(e.what()) + "; the run goes on unrecorded";
    warnings_.push_back("run: " + why);
    std::fprintf(stderr, "run: warning: %s\n", why.c_str());
    const double time_s = kernel_ ? kernel_->state().data().time : 0.0;
    if (log_) std::fprintf(log_.get(), "%.6f\trun\twarning: %s\n", time_s, why.c_str());
  }
}

// the run's result and its identity close the recording, so that the file alone says what ran
// and how it ended
void Session::CloseRecording(const RunRecord& record, const nlohmann::json& result_json) {
  const double end_s = kernel_->state().data().time;
  Record([&](RunRecording& r) {
    r.Attach("result.json",
             result_json.dump(2, ' ', false, nlohmann::json::error_handler_t::replace),
             "application/json", end_s);
    std::map<std::string, std::string> identity = {{"unimouse_version", UnimouseVersion()},
                                                   {"seed", std::to_string(options_.seed)},
                                                   {"status", record.status}};
    for (size_t i = 0; i < robots_.size(); ++i) {
      const std::string key = robots_.size() == 1 ? "robot" : "robot." + robots_[i].name;
      identity[key + "_sha256"] = robots_[i].sha256;
    }
    if (!scenario_sha256_.empty()) identity["scenario_sha256"] = scenario_sha256_;
    if (record.maze) identity["maze_sha256"] = record.maze->sha256;
    r.AddMetadata("unimouse.run", identity);
    r.Close();
  });
  recording_.reset();
}

RunRecord Session::Finish(std::optional<ViewRecord> view) {
  UNIMOUSE_DEMAND(!finished_);
  finished_ = true;
  progress_.reset();
  // a signal stops the run between two steps: what the result says, and exit code 3
  if (const std::string why = interruption(); !why.empty() && fault_.empty()) {
    interrupted_ = why + " at " + Seconds3(kernel_->state().data().time) + " s";
  }
  try {
    if (scenario_ && fault_.empty() && interrupted_.empty()) scenario_->Finish();
  } catch (const RuntimeFault& e) {
    fault_ = e.what();
  }
  // the count of the events sim.event left out, as the kernel counts the lines it held back
  if (scenario_ && scenario_->events_not_kept() > 0) {
    kernel_->Log(UNIMOUSE_LOG_INFO, "scenario",
                 "sim.event: " + std::to_string(scenario_->events_not_kept()) +
                     " events after the first " + std::to_string(kMaxScenarioEvents) +
                     " were counted, not recorded");
  }
  pictures_->Finish();
  kernel_->Finish();
  // drawn only from what a firmware reported: no connection, no picture of its beliefs
  const bool firmware_maze =
      maze_ && kernel_->declared(UNIMOUSE_TRAIT_FIRMWARE) && !beliefs_.empty();
  if (firmware_maze) DrawFirmwareMaze();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();

  // the run's record is written whatever happened to the run
  const mjData& d = kernel_->state().data();
  RunRecord r;
  r.status = !fault_.empty() ? "fault" : !interrupted_.empty() ? "interrupted" : "completed";
  r.error = !fault_.empty() ? fault_ : interrupted_;
  r.seed = options_.seed;
  r.duration_s = duration_s_;
  r.sim_time_s = d.time;
  r.steps = kernel_->state().step();
  r.wall_time_s = wall_s;
  r.real_time_factor = wall_s > 0 ? d.time / wall_s : 0.0;
  r.wall_time_split = kernel_->tick_times();
  r.firmware_paced = kernel_->firmware_paced();
  r.collision_proxy_overflows = kernel_->world().proxy_overflows();
  r.robot_name = robots_.front().spec.name;
  r.maze = maze_record_;
  for (size_t i = 0; i < robots_.size(); ++i) {
    const Robot& robot = robots_[i];
    r.robots.push_back({robot.name,
                        {robot.file, robot.sha256},
                        robot.driver,
                        kernel_->world().RobotPose(d, static_cast<int>(i)),
                        kernel_->contacts().wall_contacts(static_cast<int>(i)),
                        kernel_->contacts().robot_contacts(static_cast<int>(i)),
                        robot.restarts});
  }
  const bool ended = fault_.empty() && interrupted_.empty();
  r.exit_code = ended ? kExitPassed : kExitRuntimeFault;
  if (scenario_) {
    ScenarioRunRecord& s = r.scenario.emplace();
    s.name = scenario_->name();
    s.file = {scenario_file_, scenario_sha256_};
    s.params = scenario_->param_values();
    s.outcome = scenario_->outcome();
    if (s.outcome.status == "running") {
      s.outcome.status = !fault_.empty()         ? "error"
                         : !interrupted_.empty() ? "interrupted"
                                                 : "failed";
      s.outcome.reason = !fault_.empty() ? fault_
                         : !interrupted_.empty()
                             ? interrupted_
                             : "not decided when the run ended at " + Seconds3(d.time) + " s";
    }
    s.hud = scenario_->hud();
    s.traceback = scenario_->traceback();
    if (ended) r.exit_code = s.outcome.status == "passed" ? kExitPassed : kExitFailed;
  }
  if (pace_) r.real_time_pacing = pacer_->Report();
  r.pictures_written = pictures_->written();
  if (r.pictures_written > 0) r.pictures_renderer = pictures_->renderer();
  if (r.pictures_written == 0) r.pictures_unavailable = no_pictures_;
  r.firmware_maze = firmware_maze;
  r.measurements = measurements_;
  if (kernel_->declared(UNIMOUSE_TRAIT_FIRMWARE)) {
    r.restarts = 0;
    for (const Robot& robot : robots_) *r.restarts += robot.restarts;
  }
  r.contacts = kernel_->contacts().contacts();
  r.contacts_not_kept = kernel_->contacts().contacts_not_kept();
  r.warnings = warnings_;
  r.view = view;
  const nlohmann::json json = RunRecordJson(r);
  WriteResultRecord(options_.out_dir, json);
  CloseRecording(r, json);
  return r;
}

}  // namespace unimouse
