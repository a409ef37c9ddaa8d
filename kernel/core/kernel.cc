// SPDX-License-Identifier: GPL-3.0-or-later
#include "kernel.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "component_config.h"
#include "mujoco_guard.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

// the writer of an input signal: the world outside the robot
constexpr int kOutsideWriter = -2;

using Clock = std::chrono::steady_clock;
double Seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

std::string Names(const mjModel& m, mjtObj type, int count) {
  std::string out;
  for (int i = 0; i < count; ++i) {
    const char* name = mj_id2name(&m, type, i);
    if (name == nullptr || *name == '\0') continue;
    out += (out.empty() ? "" : ", ") + std::string(name);
  }
  return out.empty() ? "none" : out;
}

}  // namespace

// what bind-time lookups need to resolve names and to say where a failure comes from
struct Kernel::BindSession {
  Kernel* kernel;
  int component;
  std::string prefix;  // "file:line:col: component 'x' (type): "
  std::string error;
  std::string names;  // what the component's robot puts before its names: "" or "robot/"

  int Lookup(mjtObj type, const char* kind, const char* name, int count) {
    const mjModel& m = kernel->mj_model();
    const int id = mj_name2id(&m, type, (names + name).c_str());
    if (id < 0 && error.empty()) {
      error = prefix + "no " + kind + " named '" + name +
              "' (the robot has: " + Names(m, type, count) + ")";
    }
    return id;
  }

  int Signal(const char* own_name, bool write) {
    Kernel& k = *kernel;
    const std::string name = names + own_name;
    int id = k.model_.FindSignal(name);
    if (id < 0) {
      id = static_cast<int>(k.model_.signal_names.size());
      k.model_.signal_names.emplace_back(name);
      k.signal_writer_.push_back(-1);
      k.signal_first_reader_.push_back(-1);
      k.signal_readers_.emplace_back();
    }
    if (write) {
      // a component may take over an input, as a test controller does
      const int writer = k.signal_writer_[id];
      if (writer >= 0) {
        if (error.empty()) {
          error = prefix + "signal '" + name + "' is already written by component '" +
                  k.model_.components[writer].name + "'; a signal has one writer";
        }
        return -1;
      }
      k.signal_writer_[id] = component;
    } else {
      if (k.signal_first_reader_[id] < 0) k.signal_first_reader_[id] = component;
      k.signal_readers_[id].push_back(component);
    }
    return id;
  }

  int Rng(const char* own_name) {
    Kernel& k = *kernel;
    const std::string name = names + own_name;
    for (const auto& existing : k.model_.rng_names) {
      if (existing == name) {
        if (error.empty()) error = prefix + "random stream '" + name + "' is already in use";
        return -1;
      }
    }
    k.model_.rng_names.emplace_back(name);
    return static_cast<int>(k.model_.rng_names.size()) - 1;
  }
};

namespace {

// what the robot file calls each of its joints in the world, and where, for messages about them
void AddJointPlaces(const RobotSpec& robot, const std::string& prefix, const mjModel& m,
                    std::vector<std::string>& places) {
  places.resize(static_cast<size_t>(m.njnt));
  const auto name = [&](const std::string& joint, const std::string& place) {
    const int id = mj_name2id(&m, mjOBJ_JOINT, (prefix + joint).c_str());
    if (id >= 0) places[id] = place;
    return id;
  };
  name(robot.chassis.name + "_free", "the chassis '" + robot.chassis.name + "' (" +
                                         robot.chassis.location.ToString() + "), moving freely");
  std::vector<const BodySpec*> bodies{&robot.chassis};
  while (!bodies.empty()) {
    const BodySpec& b = *bodies.back();
    bodies.pop_back();
    for (const BodySpec& child : b.bodies) bodies.push_back(&child);
    if (!b.joint) continue;
    const int id = name(b.joint->name, "joint '" + b.joint->name + "' of body '" + b.name + "' (" +
                                           b.joint->location.ToString() + ")");
    if (id < 0) continue;
    for (const ActuatorSpec& a : robot.actuators) {
      if (a.joint == b.joint->name) {
        places[id] += ", actuator '" + a.name + "' (" + a.location.ToString() + ")";
      }
    }
  }
}

}  // namespace

std::unique_ptr<Kernel> Kernel::Create(const RobotSpec& robot, const Maze* maze,
                                       const PluginRegistry& registry,
                                       const KernelOptions& options) {
  return Create({KernelRobot{robot, "", options.spawn}}, maze, registry, options);
}

std::unique_ptr<Kernel> Kernel::Create(const std::vector<KernelRobot>& robots, const Maze* maze,
                                       const PluginRegistry& registry,
                                       const KernelOptions& options) {
  // MuJoCo would otherwise print to stdout, write MUJOCO_LOG.TXT into the working directory
  // and, on errors, exit(1); an error becomes a fault of the run, which still writes its result
  InstallMujocoHandlers();
  UNIMOUSE_DEMAND(!robots.empty());
  std::unique_ptr<Kernel> k(new Kernel(options));
  Model& model = k->model_;
  std::vector<WorldRobot> placed;
  for (const KernelRobot& r : robots) {
    // several robots have distinct names, and the only one none
    UNIMOUSE_DEMAND(r.name.empty() == (robots.size() == 1));
    model.robot_names.push_back(r.name);
    model.robot_prefixes.push_back(r.name.empty() ? "" : r.name + "/");
    model.robot_traits.push_back(0);
    k->output_dirs_.push_back(r.name.empty() ? options.output_dir
                                             : options.output_dir + "/" + r.name);
    placed.push_back({&r.spec, model.robot_prefixes.back(), r.spawn ? r.spawn : options.spawn});
  }
  model.world = World::Build(placed, maze, options.boxes);
  for (size_t i = 0; i < robots.size(); ++i) {
    AddJointPlaces(robots[i].spec, model.robot_prefixes[i], model.mj(), model.joint_places);
  }

  // inputs are written from outside: the firmware link or a scenario
  for (size_t i = 0; i < robots.size(); ++i) {
    for (const auto& input : robots[i].spec.inputs) {
      model.signal_names.push_back(model.robot_prefixes[i] + input);
      k->signal_writer_.push_back(kOutsideWriter);
      k->signal_first_reader_.push_back(-1);
      k->signal_readers_.emplace_back();
    }
  }

  // create every component from validated parameters
  std::vector<std::string> known;
  for (const auto& [name, entry] : registry.entries()) known.push_back(name);
  for (size_t robot = 0; robot < robots.size(); ++robot) {
    for (const auto& spec : robots[robot].spec.components) {
      const PluginRegistry::Entry* entry = registry.Find(spec.type);
      if (entry == nullptr) {
        const std::string near = NearestWord(spec.type, known);
        throw InputError(spec.location.ToString() + ": component '" + spec.name +
                         "': unknown type '" + spec.type + "'" +
                         (near.empty() ? "" : " (did you mean '" + near + "'?)") +
                         "; `unimouse plugins` lists the types found");
      }
      unimouse_config config = ValidateParams(*entry->type, spec);
      if (options.trust_robot_file) config.from_data_file.clear();
      ComponentInstance c;
      c.type = entry->type;
      c.name = model.robot_prefixes[robot] + spec.name;
      c.file_name = spec.name;
      c.robot = static_cast<int>(robot);
      c.location = spec.location;
      char error[512] = "";
      c.self = c.type->create(&config, &ConfigHost(), error, sizeof(error));
      if (c.self == nullptr) {
        throw InputError(spec.location.ToString() + ": component '" + spec.name + "' (" +
                         spec.type + "): " + error);
      }
      const double period_s = spec.period_s.value_or(c.type->default_period_s);
      if (period_s > 0) {
        const double steps = period_s / k->timestep_s();
        c.every_n_steps = static_cast<int>(std::lround(steps));
        if (c.every_n_steps < 1 || std::fabs(steps - c.every_n_steps) > 1e-6 * steps) {
          k->model_.components.push_back(c);  // destroyed with the model
          std::ostringstream why;
          why << spec.location.ToString() << ": component '" << spec.name << "': period_s "
              << period_s << " is not a whole number of " << k->timestep_s() << " s physics steps";
          throw InputError(why.str());
        }
      }
      k->model_.components.push_back(c);
    }
  }

  for (size_t i = 0; i < k->model_.components.size(); ++i) k->BindComponent(static_cast<int>(i));

  // every signal read must have a writer
  for (size_t s = 0; s < k->model_.signal_names.size(); ++s) {
    if (k->signal_writer_[s] == -1) {
      const ComponentInstance& reader = k->model_.components[k->signal_first_reader_[s]];
      throw InputError(reader.location.ToString() + ": component '" + reader.name +
                       "' reads signal '" + k->model_.signal_names[s] +
                       "', which no component writes");
    }
  }

  // within a phase components run in YAML order: a reader before its writer sees, in the same
  // phase, the value of the previous tick
  for (size_t s = 0; s < k->model_.signal_names.size(); ++s) {
    for (int reader : k->signal_readers_[s]) {
      if (reader < k->signal_writer_[s]) {
        k->model_.early_reads.push_back({static_cast<int>(s), reader, k->signal_writer_[s]});
      }
    }
  }

  k->state_ = std::make_unique<State>(k->mj_model(), k->model_.component_state_size,
                                      static_cast<int>(k->model_.signal_names.size()));
  k->message_cursor_.assign(k->model_.components.size(), 0);
  k->pace_setter_.assign(k->model_.components.size(), 0);
  if (options.start_components) {
    for (const std::string& dir : k->output_dirs_) {
      std::error_code error;  // a folder that cannot be made fails where a file is written
      std::filesystem::create_directories(dir, error);
    }
    for (size_t i = 0; i < k->model_.components.size(); ++i) {
      k->StartComponent(static_cast<int>(i));
    }
  }
  k->Reset();
  return k;
}

void Kernel::BindComponent(int index) {
  ComponentInstance& c = model_.components[index];
  BindSession session{
      this, index,
      c.location.ToString() + ": component '" + c.name + "' (" + c.type->name + "): ", "",
      model_.robot_prefixes[c.robot]};
  unimouse_bind b{};
  b.size = sizeof(b);
  b.ctx = &session;
  b.model = &mj_model();
  b.timestep_s = timestep_s();
  b.component_name = c.file_name.c_str();
  b.period_s = c.every_n_steps * timestep_s();
  b.output_dir = output_dirs_[c.robot].c_str();
  if (const Maze* maze = world().maze()) {
    b.maze_width_cells = maze->width();
    b.maze_height_cells = maze->height();
    b.maze_cell_m = maze->dimensions().cell_m;
    b.maze_goal_x0 = b.maze_goal_y0 = kMaxMazeSide_cells;
    for (const Cell& g : maze->goals()) {
      b.maze_goal_x0 = std::min(b.maze_goal_x0, g.x);
      b.maze_goal_y0 = std::min(b.maze_goal_y0, g.y);
      b.maze_goal_x1 = std::max(b.maze_goal_x1, g.x);
      b.maze_goal_y1 = std::max(b.maze_goal_y1, g.y);
    }
    const int area = (b.maze_goal_x1 - b.maze_goal_x0 + 1) * (b.maze_goal_y1 - b.maze_goal_y0 + 1);
    b.maze_goal_is_rectangle = static_cast<int>(maze->goals().size()) == area;
  }
  b.joint = [](void* ctx, const char* name) {
    auto* s = static_cast<BindSession*>(ctx);
    return s->Lookup(mjOBJ_JOINT, "joint", name, s->kernel->mj_model().njnt);
  };
  b.actuator = [](void* ctx, const char* name) {
    auto* s = static_cast<BindSession*>(ctx);
    return s->Lookup(mjOBJ_ACTUATOR, "actuator", name, s->kernel->mj_model().nu);
  };
  b.site = [](void* ctx, const char* name) {
    auto* s = static_cast<BindSession*>(ctx);
    return s->Lookup(mjOBJ_SITE, "site", name, s->kernel->mj_model().nsite);
  };
  b.body = [](void* ctx, const char* name) {
    auto* s = static_cast<BindSession*>(ctx);
    return s->Lookup(mjOBJ_BODY, "body", name, s->kernel->mj_model().nbody);
  };
  b.signal_read = [](void* ctx, const char* name) {
    return static_cast<BindSession*>(ctx)->Signal(name, false);
  };
  b.signal_write = [](void* ctx, const char* name) {
    return static_cast<BindSession*>(ctx)->Signal(name, true);
  };
  b.rng_stream = [](void* ctx, const char* name) {
    return static_cast<BindSession*>(ctx)->Rng(name);
  };
  b.set_state_size = [](void* ctx, int nstate) {
    auto* s = static_cast<BindSession*>(ctx);
    s->kernel->model_.components[s->component].nstate = nstate < 0 ? 0 : nstate;
  };
  b.declare_beam = [](void* ctx, int site, int length_signal, double range_max_m) {
    auto* s = static_cast<BindSession*>(ctx);
    Model& model = s->kernel->model_;
    const bool valid = site >= 0 && site < s->kernel->mj_model().nsite && length_signal >= 0 &&
                       length_signal < static_cast<int>(model.signal_names.size()) &&
                       range_max_m > 0;
    if (!valid) {
      if (s->error.empty()) s->error = s->prefix + "declared a beam with an unknown site or signal";
      return;
    }
    model.beams.push_back({site, length_signal, range_max_m});
  };
  b.declare_traits = [](void* ctx, int traits) {
    auto* s = static_cast<BindSession*>(ctx);
    Model& model = s->kernel->model_;
    model.traits |= traits;
    model.robot_traits[model.components[s->component].robot] |= traits;
  };

  char error[512] = "";
  const int failed = c.type->bind(c.self, &b, error, sizeof(error));
  if (!session.error.empty()) throw InputError(session.error);
  if (failed) throw InputError(session.prefix + error);
  c.state_offset = model_.component_state_size;
  model_.component_state_size += c.nstate;
}

void Kernel::StartComponent(int index) {
  const ComponentInstance& c = model_.components[index];
  if (c.type->start == nullptr) return;
  char error[512] = "";
  if (c.type->start(c.self, error, sizeof(error)) != 0) {
    throw InputError(c.location.ToString() + ": component '" + c.name + "' (" + c.type->name +
                     "): " + error);
  }
}

void Kernel::RunHook(int index, void (*hook)(const void*, const unimouse_tick*)) {
  const ComponentInstance& c = model_.components[index];

  // messages logged since the component last ran; the views cover every stored message
  for (size_t i = message_views_.size(); i < messages_.size(); ++i) {
    const StoredMessage& m = messages_[i];
    message_views_.push_back({m.time_s, m.level, m.source.c_str(), m.text.c_str()});
  }
  const size_t seen = message_cursor_[index];
  message_cursor_[index] = message_views_.size();

  HookContext context{this, index};
  unimouse_tick t{};
  t.size = sizeof(t);
  t.ctx = &context;
  t.model = &mj_model();
  t.data = &state_->data();
  t.state = state_->component_state().data() + c.state_offset;
  t.nstate = c.nstate;
  t.signals = state_->signals().data();
  t.step = state_->step();
  t.time_s = state_->data().time;
  t.rng_uniform = [](void* ctx, int stream) {
    return static_cast<HookContext*>(ctx)->kernel->state_->rngs()[stream].Uniform();
  };
  t.rng_normal = [](void* ctx, int stream) {
    return static_cast<HookContext*>(ctx)->kernel->state_->rngs()[stream].Normal();
  };
  t.ray_cast = [](void* ctx, const double origin[3], const double direction[3], double max_m) {
    Kernel& k = *static_cast<HookContext*>(ctx)->kernel;
    // no exception crosses back into the component: the fault ends the run after its hook
    const int robot = k.model_.components[static_cast<HookContext*>(ctx)->component].robot;
    try {
      return k.model_.world->CastRay(k.state_->data(), origin, direction, max_m, robot);
    } catch (const RuntimeFault& e) {
      if (k.fault_.empty()) k.fault_ = e.what();
      return -1.0;
    }
  };
  t.log = [](void* ctx, int level, const char* message) {
    auto* h = static_cast<HookContext*>(ctx);
    h->kernel->Emit(level, h->kernel->model_.components[h->component].name, message);
  };
  t.messages = message_views_.data() + seen;
  t.nmessages = static_cast<int>(message_views_.size() - seen);
  t.report = [](void* ctx, const unimouse_report* report) {
    auto* h = static_cast<HookContext*>(ctx);
    if (report == nullptr || report->size < sizeof(unimouse_report)) return;
    const ComponentInstance& from = h->kernel->model_.components[h->component];
    for (const auto& listener : h->kernel->report_listeners_) {
      listener(from.name, from.robot, *report);
    }
  };
  t.set_firmware_paced = [](void* ctx, int paced) {
    auto* h = static_cast<HookContext*>(ctx);
    char& setter = h->kernel->pace_setter_[h->component];
    h->kernel->paced_count_ += (paced != 0) - setter;
    setter = paced != 0;
  };
  // a component's own call into MuJoCo (a plugin may make them) is guarded at its hook, and its
  // error is the component's, as one it logged
  try {
    GuardMujoco([&] { hook(c.self, &t); });
  } catch (const RuntimeFault& e) {
    Emit(UNIMOUSE_LOG_ERROR, c.name, e.what());
  }
}

void Kernel::Emit(int level, const std::string& component, const std::string& message) {
  // a firmware sending junk, or a component in a loop, must not fill the disk or the memory:
  // errors always pass, warnings and log lines up to a budget, then a note and a count
  if (level != UNIMOUSE_LOG_ERROR) {
    MessageBudget& b = message_budgets_[component];
    const bool warning = level == UNIMOUSE_LOG_WARNING;
    bool& full = warning ? b.warnings_full : b.log_full;
    if (!full) {
      full = warning ? b.warnings_shown == kMaxWarningsShown
                     : b.log_shown_bytes + message.size() > kMaxLogShown_bytes;
      if (full) {
        Store(UNIMOUSE_LOG_WARNING, component,
              warning ? "more than " + std::to_string(kMaxWarningsShown) +
                            " warnings: later ones are counted, not shown"
                      : "more than " + std::to_string(kMaxLogShown_bytes >> 20) +
                            " MiB of log lines: later ones are counted, not shown");
      }
    }
    if (full) {
      ++b.held_back;
      return;
    }
    if (warning) {
      ++b.warnings_shown;
    } else {
      b.log_shown_bytes += message.size();
    }
  }
  Store(level, component, Shortened(message, kMaxMessage_bytes));
}

void Kernel::Store(int level, const std::string& component, const std::string& message) {
  // stored only: views are added between hooks, so a hook's view array never moves under it
  messages_.push_back({state_->data().time, level, component, message});
  if (level == UNIMOUSE_LOG_ERROR && fault_.empty()) {
    std::ostringstream out;
    out << "component '" << component << "' failed at t=" << state_->data().time
        << " s: " << message;
    fault_ = out.str();
  }
  for (const auto& listener : listeners_) listener(state_->data().time, level, component, message);
  if (options_.log_sink) {
    options_.log_sink(state_->data().time, level, component, message);
  } else if (level != UNIMOUSE_LOG_INFO && level != UNIMOUSE_LOG_DETAIL) {
    std::cerr << component << ": " << message << "\n";
  }
}

void Kernel::Finish() {
  for (const auto& [source, budget] : message_budgets_) {
    if (budget.held_back > 0) {
      Store(UNIMOUSE_LOG_WARNING, source,
            std::to_string(budget.held_back) + " more messages were not shown");
    }
  }
  message_budgets_.clear();
  for (size_t i = 0; i < model_.components.size(); ++i) {
    const ComponentInstance& c = model_.components[i];
    if (c.type->finish != nullptr) RunHook(static_cast<int>(i), c.type->finish);
  }
  fault_.clear();
}

void Kernel::ForgetSeenMessages() {
  size_t seen_by_all = message_views_.size();
  for (size_t i = 0; i < model_.components.size(); ++i) {
    const ComponentInstance& c = model_.components[i];
    if (c.type->sense != nullptr || c.type->actuate != nullptr || c.type->finish != nullptr) {
      seen_by_all = std::min(seen_by_all, message_cursor_[i]);
    }
  }
  // erasing at the front of a deque leaves the other elements, and the views into them, in place
  if (seen_by_all < 1024) return;
  messages_.erase(messages_.begin(), messages_.begin() + static_cast<long>(seen_by_all));
  message_views_.erase(message_views_.begin(),
                       message_views_.begin() + static_cast<long>(seen_by_all));
  for (auto& cursor : message_cursor_) cursor = cursor > seen_by_all ? cursor - seen_by_all : 0;
}

void Kernel::ThrowIfFaulted() {
  if (!fault_.empty()) {
    const std::string fault = fault_;
    fault_.clear();
    throw RuntimeFault(fault);
  }
}

void Kernel::Reset() {
  const mjModel& m = mj_model();
  mjData& d = state_->data();
  GuardMujoco([&] {
    mj_resetData(&m, &d);
    for (int r = 0; r < robot_count(); ++r) model_.world->PlaceRobot(d, model_.world->spawn(r), r);
    model_.world->UpdateCollisionProxies(d);
    mj_forward(&m, &d);
  });

  std::fill(state_->component_state().begin(), state_->component_state().end(), 0.0);
  std::fill(state_->signals().begin(), state_->signals().end(), 0.0);
  state_->rngs().clear();
  for (const auto& name : model_.rng_names) state_->rngs().emplace_back(seed_, name);
  state_->set_step(0);
  std::fill(pace_setter_.begin(), pace_setter_.end(), 0);
  paced_count_ = 0;
  tick_times_ = {};
  contacts_ = ContactWatch(robot_count());

  messages_.clear();
  message_views_.clear();
  std::fill(message_cursor_.begin(), message_cursor_.end(), 0);
  message_budgets_.clear();
  for (size_t i = 0; i < model_.components.size(); ++i) {
    const ComponentInstance& c = model_.components[i];
    if (c.type->reset != nullptr) RunHook(static_cast<int>(i), c.type->reset);
  }
  ThrowIfFaulted();
}

double Kernel::RunPhase(int64_t step,
                        void (*unimouse_component_type::*hook)(const void*, const unimouse_tick*)) {
  double pace_setter_s = 0;
  for (size_t i = 0; i < model_.components.size(); ++i) {
    const ComponentInstance& c = model_.components[i];
    if (c.type->*hook == nullptr || step % c.every_n_steps != 0) continue;
    if (!pace_setter_[i]) {
      RunHook(static_cast<int>(i), c.type->*hook);
      continue;
    }
    const auto start = Clock::now();
    RunHook(static_cast<int>(i), c.type->*hook);
    pace_setter_s += Seconds(Clock::now() - start);
  }
  return pace_setter_s;
}

void Kernel::Step() {
  const mjModel& m = mj_model();
  mjData& d = state_->data();
  const int64_t step = state_->step();

  // wall time by part, for the run's report; it never feeds back into the run
  const auto start = Clock::now();
  if (boundary_hook_) boundary_hook_();
  const auto scenario_done = Clock::now();
  GuardMujoco([&] {
    model_.world->UpdateCollisionProxies(d);
    mj_step1(&m, &d);
  });
  contacts_.Update(*model_.world, m, d);
  const auto step1_done = Clock::now();

  double pace_setter_s = RunPhase(step, &unimouse_component_type::sense);
  ThrowIfFaulted();
  pace_setter_s += RunPhase(step, &unimouse_component_type::actuate);
  ThrowIfFaulted();
  const auto hooks_done = Clock::now();

  GuardMujoco([&] { mj_step2(&m, &d); });
  const auto step2_done = Clock::now();
  tick_times_.scenario_s += Seconds(scenario_done - start);
  tick_times_.physics_s += Seconds(step1_done - scenario_done) + Seconds(step2_done - hooks_done);
  tick_times_.components_s += Seconds(hooks_done - step1_done) - pace_setter_s;
  tick_times_.firmware_s += pace_setter_s;
  state_->set_step(step + 1);
  ForgetSeenMessages();

  // MuJoCo resets a diverged simulation silently apart from this warning, whose info is the
  // index of the first bad acceleration or velocity (a dof) or position (a qpos entry)
  const char* what[] = {"acceleration", "velocity", "position"};
  const int warnings[] = {mjWARN_BADQACC, mjWARN_BADQVEL, mjWARN_BADQPOS};
  for (int i = 0; i < 3; ++i) {
    const mjWarningStat& warning = d.warning[warnings[i]];
    if (warning.number == 0) continue;
    const int index = warning.lastinfo;
    int joint = -1;
    if (warnings[i] != mjWARN_BADQPOS && index >= 0 && index < m.nv) {
      joint = m.dof_jntid[index];
    }
    for (int j = 0; warnings[i] == mjWARN_BADQPOS && j < m.njnt; ++j) {
      if (m.jnt_qposadr[j] <= index) joint = j;
    }
    std::ostringstream out;
    out << "physics diverged at t=" << d.time << " s: the " << what[i] << " of ";
    if (joint >= 0 && !model_.joint_places[joint].empty()) {
      out << model_.joint_places[joint];
    } else {
      out << "degree of freedom " << index;
    }
    out << " became infinite or not a number; check masses, inertias, timestep and controls";
    throw RuntimeFault(out.str());
  }
}

}  // namespace unimouse
