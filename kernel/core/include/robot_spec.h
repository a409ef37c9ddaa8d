// SPDX-License-Identifier: GPL-3.0-or-later
// A robot as described by its YAML file: a tree of rigid bodies with joints, geoms and sites,
// the actuators MuJoCo applies torques through, and the components (plugins) that model its
// electronics. Plain data; the world builder turns it into MJCF.
#ifndef UNIMOUSE_CORE_ROBOT_SPEC_H_
#define UNIMOUSE_CORE_ROBOT_SPEC_H_

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "yaml_doc.h"

namespace unimouse {

using Vec3 = std::array<double, 3>;

struct GeomSpec {
  std::string name;
  std::string type;       ///< box, sphere, cylinder or capsule
  Vec3 size_m{};          ///< box: full extents along x, y, z
  double radius_m = 0;    ///< sphere, cylinder, capsule
  double length_m = 0;    ///< cylinder, capsule: along the geom's z axis
  Vec3 pos_m{};           ///< in the body frame
  Vec3 euler_deg{};       ///< xyz rotation in the body frame
  double mass_kg = 0;     ///< a body's geoms must weigh something in total
  double friction = 0.6;  ///< Coulomb sliding coefficient
  bool contact = true;    ///< false: seen and weighed, never touched
  std::array<double, 4> rgba{0.6, 0.6, 0.6, 1};
  SourceLocation location;
};

struct SiteSpec {
  std::string name;
  Vec3 pos_m{};
  Vec3 euler_deg{};  ///< the site's x axis is where a sensor on it points
  SourceLocation location;
};

struct JointSpec {
  std::string name;
  std::string type;    ///< hinge or ball
  Vec3 axis{0, 1, 0};  ///< hinge axis in the body frame
  double damping_nm_s = 0;
  double armature_kg_m2 = 0;
  SourceLocation location;
};

struct BodySpec {
  std::string name;
  Vec3 pos_m{};  ///< relative to the parent body; ignored for the chassis
  Vec3 euler_deg{};
  std::optional<JointSpec> joint;  ///< none for the chassis, which floats freely
  std::vector<GeomSpec> geoms;
  std::vector<SiteSpec> sites;
  std::vector<BodySpec> bodies;
  SourceLocation location;
};

/// A torque actuator on a hinge; ctrl is the joint torque in N m.
struct ActuatorSpec {
  std::string name;
  std::string joint;
  SourceLocation location;
};

/// One entry of the components list; params are validated against the type's schema later.
struct ComponentSpec {
  std::string type;
  std::string name;
  std::optional<double> period_s;
  YamlNode params;
  SourceLocation location;
};

/// Shortest physics step a robot file may ask for: 0.1 ms, ten thousand steps a simulated second.
inline constexpr double kMinTimestep_s = 1e-4;
/// Longest physics step: 10 ms.
inline constexpr double kMaxTimestep_s = 0.01;

struct RobotSpec {
  std::string name;
  std::string file;
  double timestep_s = 0.001;
  std::string integrator = "Euler";
  BodySpec chassis;
  std::vector<ActuatorSpec> actuators;
  /// Signals the outside world writes (the firmware link, a scenario): components may read them
  /// without a component writing them.
  std::vector<std::string> inputs;
  std::vector<ComponentSpec> components;
};

/// One key a robot file may give, as the loader reads it. The loader accepts exactly the keys of
/// this table, and docs/robots.md is written from it (`unimouse robot-schema --markdown`); a
/// key's unit is in its name.
struct RobotKey {
  const char* part;  ///< robot, body, moving body, joint, geom, site, actuator, component
  const char* key;
  const char* type;          ///< string, number, boolean, 3 numbers, a map or a list of them
  const char* default_text;  ///< "required", or what applies when the key is left out
  const char* range;         ///< the values allowed beyond the type; "" for any
  const char* meaning;
};

/// Every key of a robot file, part by part in the order docs/robots.md shows them. "body" keys
/// are those of every body, the chassis too; "moving body" ones those of the others.
std::span<const RobotKey> RobotKeys();

/// Returns the keys of one part of a robot file, in table order.
std::vector<std::string> RobotKeysOf(std::string_view part);

/// Reads and validates a robot file; throws InputError with file:line:col.
RobotSpec LoadRobotSpec(const std::string& path);
/// Reads and validates robot YAML text; `file` names it in errors.
RobotSpec ParseRobotSpec(const std::string& text, const std::string& file);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_ROBOT_SPEC_H_
