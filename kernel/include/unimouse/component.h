// SPDX-License-Identifier: GPL-3.0-or-later
// The C++ face of the plugin ABI. A component is a class with a Params struct, constructed from
// validated parameters, bound once to the MuJoCo model, and const ever after: what evolves lives
// in its state slice, owned by the kernel.
//
//   class DcMotor final : public unimouse::Component {
//    public:
//     static constexpr const char* kTypeName = "unimouse.dc_motor";
//     static constexpr const char* kSummary = "brushed DC motor, eq. 3.15";
//     static constexpr double kDefaultPeriod_s = 0;
//     using Params = DcMotorParams;
//     explicit DcMotor(Params params);
//     void Bind(unimouse::BindContext& ctx) override;
//     void Actuate(const unimouse::ActuateContext& ctx) const override;
//   };
//
//   UNIMOUSE_EXPORT_PLUGIN(DcMotor)  // in the plugin's own plugin.cc only
#ifndef UNIMOUSE_COMPONENT_H_
#define UNIMOUSE_COMPONENT_H_

#include <cstring>
#include <exception>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

#include "unimouse/errors.h"
#include "unimouse/params.h"
#include "unimouse/plugin_abi.h"

namespace unimouse {

/// Index of a named scalar signal shared between components.
struct SignalId {
  int index = -1;
};

/// Index of a named, seeded random stream.
struct RngId {
  int index = -1;
};

/// Resolves names once, at bind time. A failed lookup stops Bind; the kernel reports it with the
/// component's YAML location.
class BindContext {
 public:
  explicit BindContext(const unimouse_bind& b) : b_(b) {}

  const mjModel& model() const { return *b_.model; }
  double timestep_s() const { return b_.timestep_s; }
  /// Returns the time between two runs of this component's hooks.
  double period_s() const { return b_.period_s; }
  /// Returns the instance's name in the robot file.
  std::string name() const { return b_.component_name; }
  /// Returns the directory the run writes its files into.
  std::string output_dir() const { return b_.output_dir; }
  /// Returns `relative` inside the run's output directory. Throws InputError for an absolute
  /// path or one with a '..' part: a robot file writes inside the output directory only.
  std::string OutputFile(const std::string& relative) const {
    size_t begin = 0;
    while (begin <= relative.size()) {
      size_t end = relative.find('/', begin);
      if (end == std::string::npos) end = relative.size();
      if (relative.compare(begin, end - begin, "..") == 0) {
        throw InputError("'" + relative.substr(0, 200) +
                         "' leaves the output directory ('..'); give a path inside it");
      }
      begin = end + 1;
    }
    if (relative.empty() || relative[0] == '/') {
      throw InputError("'" + relative.substr(0, 200) +
                       "' is not a path inside the output directory; give a relative one");
    }
    return std::string(b_.output_dir) + "/" + relative;
  }
  int JointId(const std::string& name) const { return Check(b_.joint(b_.ctx, name.c_str())); }
  int ActuatorId(const std::string& name) const { return Check(b_.actuator(b_.ctx, name.c_str())); }
  int SiteId(const std::string& name) const { return Check(b_.site(b_.ctx, name.c_str())); }
  int BodyId(const std::string& name) const { return Check(b_.body(b_.ctx, name.c_str())); }
  SignalId ReadSignal(const std::string& name) const {
    return {Check(b_.signal_read(b_.ctx, name.c_str()))};
  }
  SignalId WriteSignal(const std::string& name) const {
    return {Check(b_.signal_write(b_.ctx, name.c_str()))};
  }
  RngId Rng(const std::string& name) const { return {Check(b_.rng_stream(b_.ctx, name.c_str()))}; }
  void SetStateSize(int nstate) const { b_.set_state_size(b_.ctx, nstate); }
  /// The maze the world was built from (see unimouse_bind); width_cells 0 on an open floor or
  /// from a kernel older than the field.
  struct MazeInfo {
    int width_cells = 0;
    int height_cells = 0;
    double cell_m = 0;
    int goal_x0 = 0, goal_y0 = 0, goal_x1 = 0, goal_y1 = 0;
    bool goal_is_rectangle = true;
  };
  MazeInfo maze() const {
    if (!UNIMOUSE_HAS_FIELD(&b_, unimouse_bind, maze_goal_is_rectangle)) return {};
    return {
        b_.maze_width_cells, b_.maze_height_cells, b_.maze_cell_m,  b_.maze_goal_x0,
        b_.maze_goal_y0,     b_.maze_goal_x1,      b_.maze_goal_y1, b_.maze_goal_is_rectangle != 0};
  }
  /// Declares a beam the host draws: from `site` along its x axis, `length` metres long; a
  /// length of range_max_m or more is a miss.
  void DeclareBeam(int site, SignalId length, double range_max_m) const {
    if (UNIMOUSE_HAS_FIELD(&b_, unimouse_bind, declare_beam)) {
      b_.declare_beam(b_.ctx, site, length.index, range_max_m);
    }
  }
  /// Declares what the component is to the run: UNIMOUSE_TRAIT_* bits, or-ed.
  void DeclareTraits(int traits) const {
    if (UNIMOUSE_HAS_FIELD(&b_, unimouse_bind, declare_traits)) {
      b_.declare_traits(b_.ctx, traits);
    }
  }

 private:
  // the kernel has already recorded why; an empty message tells the adapter to use that
  static int Check(int id) {
    if (id < 0) {
      throw InputError("");
    }
    return id;
  }

  const unimouse_bind& b_;
};

/// What every hook sees: the world, this component's state slice, signals and services.
class TickContext {
 public:
  explicit TickContext(const unimouse_tick& t) : t_(t) {}

  const mjModel& model() const { return *t_.model; }
  const mjData& data() const { return *t_.data; }
  std::span<double> state() const { return {t_.state, static_cast<size_t>(t_.nstate)}; }
  double Read(SignalId id) const { return t_.signals[id.index]; }
  void Write(SignalId id, double value) const { t_.signals[id.index] = value; }
  double Uniform(RngId id) const { return t_.rng_uniform(t_.ctx, id.index); }
  double Normal(RngId id) const { return t_.rng_normal(t_.ctx, id.index); }
  /// Returns the distance to the first non-robot surface along a unit direction, or -1.
  double CastRay(const double origin[3], const double direction[3], double max_m) const {
    return t_.ray_cast(t_.ctx, origin, direction, max_m);
  }
  /// Returns the messages logged since this component's previous hook call.
  std::span<const unimouse_message> messages() const {
    return {t_.messages, static_cast<size_t>(t_.nmessages)};
  }
  int64_t step() const { return t_.step; }
  double time_s() const { return t_.time_s; }
  void Log(const std::string& message) const { t_.log(t_.ctx, UNIMOUSE_LOG_INFO, message.c_str()); }
  void Warn(const std::string& message) const {
    t_.log(t_.ctx, UNIMOUSE_LOG_WARNING, message.c_str());
  }
  /// Logs a line too frequent for the console (one per cell, per report): the run's log keeps it.
  void Detail(const std::string& message) const {
    t_.log(t_.ctx, UNIMOUSE_LOG_DETAIL, message.c_str());
  }
  /// Logs a line of the firmware's own text (what a link receives on its log channel).
  void Firmware(const std::string& message) const {
    t_.log(t_.ctx, UNIMOUSE_LOG_FIRMWARE, message.c_str());
  }
  /// Stops the run with exit code 3 once the hook returns.
  void Fail(const std::string& message) const {
    t_.log(t_.ctx, UNIMOUSE_LOG_ERROR, message.c_str());
  }
  /// Hands the host a typed report (what a firmware believes about the maze).
  void Report(const unimouse_report& report) const {
    if (UNIMOUSE_HAS_FIELD(&t_, unimouse_tick, report)) t_.report(t_.ctx, &report);
  }
  /// Tells the host whether the firmware sets the pace (lock-step): then the run does not pace
  /// itself to the wall clock.
  void SetFirmwarePaced(bool paced) const {
    if (UNIMOUSE_HAS_FIELD(&t_, unimouse_tick, set_firmware_paced)) {
      t_.set_firmware_paced(t_.ctx, paced ? 1 : 0);
    }
  }

 protected:
  const unimouse_tick& t_;
};

/// Sense runs after mj_step1: kinematics are current and mjData is read-only.
class SenseContext : public TickContext {
 public:
  using TickContext::TickContext;
};

/// Actuate runs before mj_step2 and may write controls and applied forces.
class ActuateContext : public TickContext {
 public:
  using TickContext::TickContext;
  mjData& mutable_data() const { return *t_.data; }
};

/// Reset writes the initial values of the state slice and of the signals it writes.
using ResetContext = TickContext;

/// Base class for everything a robot YAML can instantiate.
class Component {
 public:
  virtual ~Component() = default;

  /// Resolves names to ids, declares signals, random streams and state size.
  virtual void Bind(BindContext& ctx) = 0;
  /// Opens what the instance needs outside the process (a port, a child process, a file)
  /// before the first reset of a run; never called when a robot file is only checked.
  virtual void Start() {}
  /// Writes initial values into this component's state slice.
  virtual void Reset(const ResetContext&) const {}
  /// Samples the world after mj_step1; mjData is read-only here.
  virtual void Sense(const SenseContext&) const {}
  /// Writes controls or signals before mj_step2.
  virtual void Actuate(const ActuateContext&) const {}
  /// Writes out what it still holds when the run ends, however it ends; mjData is read-only.
  virtual void Finish(const SenseContext&) const {}
};

namespace internal {

inline void CopyMessage(const char* what, char* err, int err_size) {
  if (err_size > 0) {
    std::strncpy(err, what, static_cast<size_t>(err_size) - 1);
    err[err_size - 1] = '\0';
  }
}

// calls one hook of T; an exception becomes an error that stops the run, never crosses the ABI
template <class T, class Context, void (T::*Hook)(const Context&) const>
void CallHook(const void* self, const unimouse_tick* tick) {
  try {
    (static_cast<const T*>(self)->*Hook)(Context(*tick));
  } catch (const std::exception& e) {
    tick->log(tick->ctx, UNIMOUSE_LOG_ERROR, e.what());
  }
}

}  // namespace internal

/// Returns the C type table for component class T; built once, lives for the program.
template <class T>
const unimouse_component_type* ComponentType() {
  static const param::SchemaBuilder schema = [] {
    param::SchemaBuilder builder;
    typename T::Params defaults;
    defaults.Visit(builder);
    return builder;
  }();
  static const unimouse_component_type type = [] {
    unimouse_component_type t{};
    t.size = sizeof(unimouse_component_type);
    t.name = T::kTypeName;
    t.summary = T::kSummary;
    t.nparam = static_cast<int>(schema.params().size());
    t.params = schema.params().data();
    t.default_period_s = T::kDefaultPeriod_s;
    t.create = +[](const unimouse_config* cfg, const unimouse_host* host, char* err,
                   int err_size) -> void* {
      try {
        typename T::Params params;
        param::ConfigReader reader(cfg, host);
        params.Visit(reader);
        if constexpr (requires { params.given; }) params.given = reader.given();
        if constexpr (requires { params.from_data_file; }) {
          params.from_data_file = reader.from_data_file();
        }
        return new T(std::move(params));
      } catch (const std::exception& e) {
        internal::CopyMessage(e.what(), err, err_size);
        return nullptr;
      }
    };
    t.bind = +[](void* self, const unimouse_bind* b, char* err, int err_size) -> int {
      try {
        BindContext ctx(*b);
        static_cast<T*>(self)->Bind(ctx);
        return 0;
      } catch (const std::exception& e) {
        internal::CopyMessage(e.what(), err, err_size);
        return 1;
      }
    };
    // only hooks the class overrides: the kernel skips NULL ones
    if constexpr (!std::is_same_v<decltype(&T::Start), decltype(&Component::Start)>) {
      t.start = +[](void* self, char* err, int err_size) -> int {
        try {
          static_cast<T*>(self)->Start();
          return 0;
        } catch (const std::exception& e) {
          internal::CopyMessage(e.what(), err, err_size);
          return 1;
        }
      };
    }
    if constexpr (!std::is_same_v<decltype(&T::Reset), decltype(&Component::Reset)>) {
      t.reset = &internal::CallHook<T, ResetContext, &T::Reset>;
    }
    if constexpr (!std::is_same_v<decltype(&T::Sense), decltype(&Component::Sense)>) {
      t.sense = &internal::CallHook<T, SenseContext, &T::Sense>;
    }
    if constexpr (!std::is_same_v<decltype(&T::Actuate), decltype(&Component::Actuate)>) {
      t.actuate = &internal::CallHook<T, ActuateContext, &T::Actuate>;
    }
    if constexpr (!std::is_same_v<decltype(&T::Finish), decltype(&Component::Finish)>) {
      t.finish = &internal::CallHook<T, SenseContext, &T::Finish>;
    }
    t.destroy = +[](void* self) { delete static_cast<T*>(self); };
    return t;
  }();
  return &type;
}

/// Returns the plugin table listing component classes T...; what unimouse_plugin_v1 returns.
template <class... T>
const unimouse_plugin_info* PluginInfo() {
  static const unimouse_component_type* const types[] = {ComponentType<T>()...};
  static const unimouse_plugin_info info = {
      UNIMOUSE_ABI_VERSION, sizeof(unimouse_plugin_info),   sizeof(unimouse_component_type),
      mjVERSION_HEADER,     static_cast<int>(sizeof...(T)), types};
  return &info;
}

}  // namespace unimouse

/// Exports the listed component classes from a plugin library through unimouse_plugin_v1.
#define UNIMOUSE_EXPORT_PLUGIN(...)                                                 \
  extern "C" UNIMOUSE_EXPORT const unimouse_plugin_info* unimouse_plugin_v1(void) { \
    return ::unimouse::PluginInfo<__VA_ARGS__>();                                   \
  }

#endif  // UNIMOUSE_COMPONENT_H_
