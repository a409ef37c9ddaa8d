// SPDX-License-Identifier: GPL-3.0-or-later
#include "robot_spec.h"

#include <cmath>
#include <map>
#include <set>

#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

constexpr RobotKey kRobotKeys[] = {
    {"robot", "name", "string", "required", "", "the robot's name, shown in results"},
    {"robot", "timestep_s", "number", "0.001", "[0.0001, 0.01]",
     "the physics step; components run every whole number of steps"},
    {"robot", "integrator", "string", "Euler", "Euler or implicit",
     "MuJoCo's integrator; only single-stage ones, since components sense between the two halves "
     "of a step"},
    {"robot", "chassis", "a body", "required", "",
     "the body that moves freely in the world; it has no pos_m, euler_deg or joint"},
    {"robot", "actuators", "a list of actuators", "none", "",
     "the torque actuators through which motors turn hinge joints"},
    {"robot", "inputs", "a list of strings", "none", "unique",
     "signals written from outside the robot (the firmware link, a scenario), which components "
     "may read though no component writes them"},
    {"robot", "components", "a list of components", "none", "",
     "the robot's electronics: battery, H-bridges, motors, encoders, sensors, link"},
    {"body", "name", "string", "required", "unique among bodies", "the body's name"},
    {"body", "geoms", "a list of geoms", "required", "at least one; more than 0 kg in all",
     "the body's shapes, which give it its mass and its contacts"},
    {"body", "sites", "a list of sites", "none", "", "named frames that sensors are mounted on"},
    {"body", "bodies", "a list of bodies", "none", "",
     "the bodies carried by this one, each moving on its own joint"},
    {"moving body", "pos_m", "3 numbers", "[0, 0, 0]", "",
     "where the body is in its parent's frame"},
    {"moving body", "euler_deg", "3 numbers", "[0, 0, 0]", "",
     "the body's x, y, z rotation in its parent's frame"},
    {"moving body", "joint", "a joint", "required", "", "how the body moves against its parent"},
    {"joint", "name", "string", "required", "unique among joints",
     "the name actuators give to turn it"},
    {"joint", "type", "string", "required", "hinge or ball",
     "a hinge turns about its axis; a ball turns every way and takes no actuator"},
    {"joint", "axis", "3 numbers", "required for a hinge", "not zero; not for a ball",
     "the hinge's axis in the body's frame"},
    {"joint", "damping_nm_s", "number", "0", "at least 0", "viscous friction of the joint"},
    {"joint", "armature_kg_m2", "number", "0", "at least 0",
     "rotor inertia added to the joint, such as a gearmotor's"},
    {"geom", "name", "string", "none", "unique among geoms", "the geom's name"},
    {"geom", "type", "string", "required", "box, sphere, cylinder or capsule", "the shape"},
    {"geom", "size_m", "3 numbers", "required for a box", "each more than 0; only for a box",
     "the box's full extents along x, y, z"},
    {"geom", "radius_m", "number", "required for a sphere, cylinder or capsule",
     "more than 0; not for a box", "the radius"},
    {"geom", "length_m", "number", "required for a cylinder or capsule",
     "more than 0; only for a cylinder or capsule", "the length along the geom's z axis"},
    {"geom", "pos_m", "3 numbers", "[0, 0, 0]", "", "where the geom is in its body's frame"},
    {"geom", "euler_deg", "3 numbers", "[0, 0, 0]", "",
     "the geom's x, y, z rotation in its body's frame"},
    {"geom", "mass_kg", "number", "0", "at least 0", "the geom's mass"},
    {"geom", "friction", "number", "0.6", "at least 0", "Coulomb sliding friction coefficient"},
    {"geom", "contact", "boolean", "true", "", "false: seen and weighed, never touched"},
    {"geom", "rgba", "4 numbers", "[0.6, 0.6, 0.6, 1]", "each within [0, 1]",
     "colour and opacity in pictures"},
    {"site", "name", "string", "required", "unique among sites",
     "the name a sensor's `site` parameter gives"},
    {"site", "pos_m", "3 numbers", "[0, 0, 0]", "", "where the site is in its body's frame"},
    {"site", "euler_deg", "3 numbers", "[0, 0, 0]", "",
     "the site's x, y, z rotation; its x axis is where a sensor on it points"},
    {"actuator", "name", "string", "required", "unique among actuators",
     "the name a motor's `actuator` parameter gives"},
    {"actuator", "joint", "string", "required", "a hinge joint's name",
     "the joint it turns; its control is a torque in N m"},
    {"component", "type", "string", "required", "a component type below",
     "what the component is; `unimouse plugins` lists the types found"},
    {"component", "name", "string", "required", "unique among components",
     "the component's name in messages and signals"},
    {"component", "period_s", "number", "the type's", "more than 0",
     "how often it runs, rounded to whole physics steps"},
    {"component", "params", "a map", "none", "the type's parameters below",
     "its parameters; those left out take their defaults"},
};

// names must be unique per kind across the whole robot
// MJCF is XML, whose attributes cannot carry control characters: a name with one would reach
// the physics as another name
void RequirePrintableName(const std::string& kind, const std::string& name, const YamlNode& where) {
  for (const char c : name) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      where.Fail(kind + " name must not contain control characters (tab, newline, ...)");
    }
  }
}

class NameBook {
 public:
  void Add(const std::string& kind, const std::string& name, const YamlNode& where) {
    if (name.empty()) return;
    RequirePrintableName(kind, name, where);
    auto [it, fresh] = seen_[kind].emplace(name, where.location.line);
    if (!fresh) {
      where.Fail(kind + " name '" + name + "' is already used at line " +
                 std::to_string(it->second));
    }
  }
  bool Has(const std::string& kind, const std::string& name) const {
    const auto it = seen_.find(kind);
    return it != seen_.end() && it->second.count(name) > 0;
  }

 private:
  std::map<std::string, std::map<std::string, int>> seen_;
};

double PositiveNumber(const YamlNode& node, std::string_view what) {
  const double v = node.AsNumber(what);
  if (!(v > 0)) node.Fail(std::string(what) + " must be greater than 0");
  return v;
}

double NonNegativeNumber(const YamlNode& node, std::string_view what) {
  const double v = node.AsNumber(what);
  if (v < 0) node.Fail(std::string(what) + " must not be negative");
  return v;
}

Vec3 Vector(const MapReader& r, std::string_view key, Vec3 fallback) {
  const YamlNode* n = r.Optional(key);
  return n ? n->AsNumbers<3>(key) : fallback;
}

GeomSpec ParseGeom(const YamlNode& node, NameBook& names) {
  const MapReader r(node, "geom", RobotKeysOf("geom"));
  GeomSpec g;
  g.location = node.location;
  g.name = r.String("name", "");
  names.Add("geom", g.name, node);
  const YamlNode& type = r.Required("type");
  g.type = type.AsString("type");
  if (g.type == "box") {
    r.Forbid("radius_m", "does not apply to a box (it has size_m)");
    r.Forbid("length_m", "does not apply to a box (it has size_m)");
    const YamlNode& size = r.Required("size_m");
    g.size_m = size.AsNumbers<3>("size_m");
    for (double s : g.size_m) {
      if (!(s > 0)) size.Fail("size_m entries must be greater than 0");
    }
  } else if (g.type == "sphere" || g.type == "cylinder" || g.type == "capsule") {
    r.Forbid("size_m", "does not apply to a " + g.type + " (it has radius_m)");
    if (g.type == "sphere") r.Forbid("length_m", "does not apply to a sphere");
    g.radius_m = PositiveNumber(r.Required("radius_m"), "radius_m");
    if (g.type != "sphere") g.length_m = PositiveNumber(r.Required("length_m"), "length_m");
  } else {
    type.Fail("geom type must be box, sphere, cylinder or capsule, not '" + g.type + "'");
  }
  g.pos_m = Vector(r, "pos_m", {0, 0, 0});
  g.euler_deg = Vector(r, "euler_deg", {0, 0, 0});
  if (const YamlNode* mass = r.Optional("mass_kg")) g.mass_kg = NonNegativeNumber(*mass, "mass_kg");
  if (const YamlNode* f = r.Optional("friction")) g.friction = NonNegativeNumber(*f, "friction");
  if (const YamlNode* c = r.Optional("contact")) g.contact = c->AsBool("contact");
  if (const YamlNode* c = r.Optional("rgba")) {
    const auto rgba = c->AsNumbers<4>("rgba");
    for (double v : rgba) {
      if (v < 0 || v > 1) c->Fail("rgba entries must be within [0, 1]");
    }
    g.rgba = rgba;
  }
  return g;
}

SiteSpec ParseSite(const YamlNode& node, NameBook& names) {
  const MapReader r(node, "site", RobotKeysOf("site"));
  SiteSpec s;
  s.location = node.location;
  s.name = r.Required("name").AsString("name");
  names.Add("site", s.name, node);
  s.pos_m = Vector(r, "pos_m", {0, 0, 0});
  s.euler_deg = Vector(r, "euler_deg", {0, 0, 0});
  return s;
}

JointSpec ParseJoint(const YamlNode& node, NameBook& names) {
  const MapReader r(node, "joint", RobotKeysOf("joint"));
  JointSpec j;
  j.location = node.location;
  j.name = r.Required("name").AsString("name");
  names.Add("joint", j.name, node);
  const YamlNode& type = r.Required("type");
  j.type = type.AsString("type");
  if (j.type != "hinge" && j.type != "ball") {
    type.Fail("joint type must be hinge or ball, not '" + j.type + "'");
  }
  if (j.type == "ball") r.Forbid("axis", "does not apply to a ball joint, which turns every way");
  if (j.type == "hinge") {
    const YamlNode& axis = r.Required("axis");
    j.axis = axis.AsNumbers<3>("axis");
    if (std::hypot(j.axis[0], j.axis[1], j.axis[2]) < 1e-9) axis.Fail("axis must not be zero");
  }
  if (const YamlNode* d = r.Optional("damping_nm_s")) {
    j.damping_nm_s = NonNegativeNumber(*d, "damping_nm_s");
  }
  if (const YamlNode* a = r.Optional("armature_kg_m2")) {
    j.armature_kg_m2 = NonNegativeNumber(*a, "armature_kg_m2");
  }
  return j;
}

BodySpec ParseBody(const YamlNode& node, NameBook& names, bool is_chassis) {
  std::vector<std::string> keys = RobotKeysOf("body");
  if (!is_chassis) {
    const std::vector<std::string> moving = RobotKeysOf("moving body");
    keys.insert(keys.end(), moving.begin(), moving.end());
  }
  const MapReader r(node, is_chassis ? "chassis" : "body", keys);
  BodySpec b;
  b.location = node.location;
  b.name = r.Required("name").AsString("name");
  names.Add("body", b.name, node);
  if (!is_chassis) {
    b.pos_m = Vector(r, "pos_m", {0, 0, 0});
    b.euler_deg = Vector(r, "euler_deg", {0, 0, 0});
    b.joint = ParseJoint(r.Required("joint"), names);
  }
  const YamlNode& geoms = r.Required("geoms");
  if (!geoms.IsSequence() || geoms.items.empty()) {
    geoms.Fail("geoms must be a list with at least one geom (every body needs mass)");
  }
  double mass_kg = 0;
  for (const auto& g : geoms.items) {
    b.geoms.push_back(ParseGeom(g, names));
    mass_kg += b.geoms.back().mass_kg;
  }
  // a body that moves needs mass, or the physics cannot accelerate it
  if (!(mass_kg > 0)) {
    geoms.Fail("body '" + b.name + "': its geoms weigh 0 kg in all; give one a mass_kg");
  }
  if (const YamlNode* sites = r.Optional("sites")) {
    if (!sites->IsSequence()) sites->Fail("sites must be a list");
    for (const auto& s : sites->items) b.sites.push_back(ParseSite(s, names));
  }
  if (const YamlNode* bodies = r.Optional("bodies")) {
    if (!bodies->IsSequence()) bodies->Fail("bodies must be a list");
    for (const auto& child : bodies->items) b.bodies.push_back(ParseBody(child, names, false));
  }
  return b;
}

const JointSpec* FindJoint(const BodySpec& body, const std::string& name) {
  if (body.joint && body.joint->name == name) return &*body.joint;
  for (const BodySpec& child : body.bodies) {
    if (const JointSpec* j = FindJoint(child, name)) return j;
  }
  return nullptr;
}

}  // namespace

std::span<const RobotKey> RobotKeys() { return kRobotKeys; }

std::vector<std::string> RobotKeysOf(std::string_view part) {
  std::vector<std::string> keys;
  for (const RobotKey& k : kRobotKeys) {
    if (part == k.part) keys.emplace_back(k.key);
  }
  return keys;
}

RobotSpec ParseRobotSpec(const std::string& text, const std::string& file) {
  const YamlNode root = ParseYaml(text, file);
  const MapReader r(root, "robot", RobotKeysOf("robot"));
  RobotSpec robot;
  robot.file = file;
  const YamlNode& name = r.Required("name");
  robot.name = name.AsString("name");
  RequirePrintableName("robot", robot.name, name);
  if (const YamlNode* t = r.Optional("timestep_s")) {
    robot.timestep_s = t->AsNumber("timestep_s");
    if (!(robot.timestep_s >= kMinTimestep_s && robot.timestep_s <= kMaxTimestep_s)) {
      t->Fail("timestep_s must be within [0.0001, 0.01] (docs/limits.md)");
    }
  }
  if (const YamlNode* i = r.Optional("integrator")) {
    robot.integrator = i->AsString("integrator");
    // sensing between mj_step1 and mj_step2 needs a single-stage integrator
    if (robot.integrator != "Euler" && robot.integrator != "implicit") {
      i->Fail("integrator must be Euler or implicit, not '" + robot.integrator + "'");
    }
  }

  NameBook names;
  robot.chassis = ParseBody(r.Required("chassis"), names, true);

  if (const YamlNode* actuators = r.Optional("actuators")) {
    if (!actuators->IsSequence()) actuators->Fail("actuators must be a list");
    for (const auto& node : actuators->items) {
      const MapReader a(node, "actuator", RobotKeysOf("actuator"));
      ActuatorSpec spec;
      spec.location = node.location;
      spec.name = a.Required("name").AsString("name");
      names.Add("actuator", spec.name, node);
      const YamlNode& joint = a.Required("joint");
      spec.joint = joint.AsString("joint");
      if (!names.Has("joint", spec.joint)) {
        joint.Fail("actuator '" + spec.name + "': no joint named '" + spec.joint + "'");
      }
      if (FindJoint(robot.chassis, spec.joint)->type != "hinge") {
        joint.Fail("actuator '" + spec.name + "': joint '" + spec.joint +
                   "' is a ball joint; a motor turns a hinge");
      }
      robot.actuators.push_back(spec);
    }
  }

  if (const YamlNode* inputs = r.Optional("inputs")) {
    if (!inputs->IsSequence()) inputs->Fail("inputs must be a list of signal names");
    for (const auto& item : inputs->items) {
      robot.inputs.push_back(item.AsString("input"));
      names.Add("input", robot.inputs.back(), item);
    }
  }

  if (const YamlNode* components = r.Optional("components")) {
    if (components->kind != YamlNode::Kind::kNull) {
      if (!components->IsSequence()) components->Fail("components must be a list");
      for (const auto& node : components->items) {
        const MapReader c(node, "component", RobotKeysOf("component"));
        ComponentSpec spec;
        spec.location = node.location;
        spec.type = c.Required("type").AsString("type");
        spec.name = c.Required("name").AsString("name");
        names.Add("component", spec.name, node);
        if (const YamlNode* p = c.Optional("period_s")) {
          spec.period_s = p->AsNumber("period_s");
          if (!(*spec.period_s > 0)) p->Fail("period_s must be greater than 0");
        }
        if (const YamlNode* p = c.Optional("params")) {
          spec.params = *p;
        } else {
          spec.params.location = node.location;
        }
        robot.components.push_back(std::move(spec));
      }
    }
  }
  return robot;
}

RobotSpec LoadRobotSpec(const std::string& path) {
  return ParseRobotSpec(ReadTextFile(path), path);
}

}  // namespace unimouse
