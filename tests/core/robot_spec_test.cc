// SPDX-License-Identifier: GPL-3.0-or-later
// Robot files are read strictly; every class of mistake names its file:line:col.
#include "robot_spec.h"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "inline_assets.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

constexpr const char* kTiny =
    "name: tiny\n"
    "chassis:\n"
    "  name: body\n"
    "  geoms:\n"
    "    - { type: sphere, radius_m: 0.02, mass_kg: 0.1 }\n";

// replaces the first occurrence of `from` in the tiny robot
std::string TinyWith(const std::string& from, const std::string& to) {
  std::string text = kTiny;
  text.replace(text.find(from), from.size(), to);
  return text;
}

std::string ErrorOf(const std::string& yaml) {
  try {
    ParseRobotSpec(yaml, "robot.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RobotSpecTest, ReadsAMinimalRobot) {
  const RobotSpec robot = ParseRobotSpec(kTiny, "robot.yaml");
  EXPECT_EQ(robot.name, "tiny");
  EXPECT_EQ(robot.timestep_s, 0.001);
  ASSERT_EQ(robot.chassis.geoms.size(), 1u);
  EXPECT_EQ(robot.chassis.geoms[0].radius_m, 0.02);
}

TEST(RobotSpecTest, ReadsTheBundledRobotWithTheDissertationsNumbers) {
  const RobotSpec robot = LoadRobotSpec(testing::BundledRobotPath());
  EXPECT_EQ(robot.timestep_s, 0.001);
  // table 4.1: plate 0.096 x 0.020 x 0.120 m, 0.127 kg
  const GeomSpec& plate = robot.chassis.geoms[0];
  EXPECT_EQ(plate.size_m, (Vec3{0.120, 0.096, 0.020}));
  EXPECT_EQ(plate.mass_kg, 0.127);
  ASSERT_EQ(robot.chassis.bodies.size(), 3u);
  const BodySpec& left = robot.chassis.bodies[0];
  EXPECT_EQ(left.pos_m, (Vec3{0, 0.048, 0}));  // track 0.096 m
  EXPECT_EQ(left.geoms[0].radius_m, 0.016);
  EXPECT_EQ(left.geoms[0].mass_kg, 0.01);
  EXPECT_EQ(robot.chassis.bodies[2].joint->type, "ball");
  EXPECT_EQ(robot.chassis.sites.size(), 3u);
}

TEST(RobotSpecTest, UnknownKeyGivesItsLocationAndANearMatch) {
  const std::string yaml = TinyWith("radius_m", "radus_m");
  EXPECT_EQ(ErrorOf(yaml),
            "robot.yaml:5:23: geom: unknown key 'radus_m' (did you mean 'radius_m'?)");
}

TEST(RobotSpecTest, MissingKeyPointsAtTheMapThatLacksIt) {
  EXPECT_EQ(ErrorOf(TinyWith("type: sphere, ", "")), "robot.yaml:5:7: geom: missing key 'type'");
  EXPECT_EQ(ErrorOf("chassis:\n  name: x\n"), "robot.yaml:1:1: robot: missing key 'name'");
}

TEST(RobotSpecTest, WrongTypePointsAtTheValue) {
  EXPECT_EQ(ErrorOf(TinyWith("0.1 }", "heavy }")),
            "robot.yaml:5:48: mass_kg must be a number, not 'heavy'");
  EXPECT_EQ(ErrorOf(TinyWith("  name: body", "  name: [a, b]")),
            "robot.yaml:3:9: name must be a word or text");
}

TEST(RobotSpecTest, NonFiniteNumbersAreRefused) {
  EXPECT_EQ(ErrorOf(TinyWith("0.1 }", ".inf }")),
            "robot.yaml:5:48: mass_kg must be finite, not '.inf'");
  EXPECT_EQ(ErrorOf(TinyWith("0.02", "nan")),
            "robot.yaml:5:33: radius_m must be finite, not 'nan'");
}

TEST(RobotSpecTest, OutOfRangeValuesAreRefused) {
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "timestep_s: 0.5\n"),
            "robot.yaml:6:13: timestep_s must be within [0.0001, 0.01] (docs/limits.md)");
  EXPECT_EQ(ErrorOf(TinyWith("0.02", "-0.02")), "robot.yaml:5:33: radius_m must be greater than 0");
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "integrator: RK4\n"),
            "robot.yaml:6:13: integrator must be Euler or implicit, not 'RK4'");
}

// the default the schema table documents for a key
std::string SchemaDefault(std::string_view part, std::string_view key) {
  for (const RobotKey& k : RobotKeys()) {
    if (part == k.part && key == k.key) return k.default_text;
  }
  return "not in the schema";
}

TEST(RobotSpecTest, TheSchemaDocumentsTheDefaultsTheLoaderApplies) {
  const RobotSpec robot =
      ParseRobotSpec(std::string(kTiny) +
                         "  bodies:\n"
                         "    - name: wheel\n"
                         "      joint: { name: j, type: hinge, axis: [0, 1, 0] }\n"
                         "      geoms: [{ type: sphere, radius_m: 0.01, "
                         "mass_kg: 0.01 }]\n",
                     "robot.yaml");
  EXPECT_EQ(SchemaDefault("robot", "timestep_s"), "0.001");
  EXPECT_EQ(robot.timestep_s, 0.001);
  EXPECT_EQ(SchemaDefault("robot", "integrator"), "Euler");
  EXPECT_EQ(robot.integrator, "Euler");
  const GeomSpec& g = robot.chassis.geoms[0];
  EXPECT_EQ(SchemaDefault("geom", "friction"), "0.6");
  EXPECT_EQ(g.friction, 0.6);
  EXPECT_EQ(SchemaDefault("geom", "contact"), "true");
  EXPECT_TRUE(g.contact);
  EXPECT_EQ(SchemaDefault("geom", "rgba"), "[0.6, 0.6, 0.6, 1]");
  EXPECT_EQ(g.rgba, (std::array<double, 4>{0.6, 0.6, 0.6, 1}));
  const JointSpec& j = *robot.chassis.bodies[0].joint;
  EXPECT_EQ(SchemaDefault("joint", "damping_nm_s"), "0");
  EXPECT_EQ(j.damping_nm_s, 0);
  EXPECT_EQ(SchemaDefault("joint", "armature_kg_m2"), "0");
  EXPECT_EQ(j.armature_kg_m2, 0);
}

TEST(RobotSpecTest, TheChassisTakesTheBodyKeysAndOtherBodiesTheMovingOnesToo) {
  EXPECT_EQ(RobotKeysOf("body"), (std::vector<std::string>{"name", "geoms", "sites", "bodies"}));
  EXPECT_EQ(RobotKeysOf("moving body"), (std::vector<std::string>{"pos_m", "euler_deg", "joint"}));
  EXPECT_EQ(ErrorOf(TinyWith("  name: body\n", "  name: body\n  pos_m: [0, 0, 0]\n")),
            "robot.yaml:4:3: chassis: unknown key 'pos_m'");
}

TEST(RobotSpecTest, TimestepsOutsideTheDocumentedRangeAreRefused) {
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "timestep_s: 1e-9\n"),
            "robot.yaml:6:13: timestep_s must be within [0.0001, 0.01] (docs/limits.md)");
  EXPECT_EQ(ParseRobotSpec(std::string(kTiny) + "timestep_s: 0.0001\n", "robot.yaml").timestep_s,
            1e-4);
}

TEST(RobotSpecTest, ABodyWhoseGeomsWeighNothingIsRefusedAtItsGeoms) {
  EXPECT_EQ(ErrorOf(TinyWith("mass_kg: 0.1", "mass_kg: 0")),
            "robot.yaml:5:5: body 'body': its geoms weigh 0 kg in all; give one a mass_kg");
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "  bodies:\n"
                                         "    - name: wheel\n"
                                         "      joint: { name: j, type: hinge, axis: [0, 1, 0] }\n"
                                         "      geoms: [{ type: sphere, radius_m: 0.01 }]\n"),
            "robot.yaml:9:14: body 'wheel': its geoms weigh 0 kg in all; give one a mass_kg");
}

TEST(RobotSpecTest, AMotorOnABallJointIsRefusedAtTheActuator) {
  EXPECT_EQ(ErrorOf(std::string(kTiny) +
                    "  bodies:\n"
                    "    - name: caster\n"
                    "      joint: { name: ball, type: ball }\n"
                    "      geoms: [{ type: sphere, radius_m: 0.01, mass_kg: 0.01 }]\n"
                    "actuators:\n  - { name: m, joint: ball }\n"),
            "robot.yaml:11:23: actuator 'm': joint 'ball' is a ball joint; a motor turns a hinge");
}

TEST(RobotSpecTest, KeysThatDoNotApplyToTheGeomTypeAreRefused) {
  EXPECT_EQ(ErrorOf(TinyWith("type: sphere", "type: box, size_m: [1, 1, 1]")),
            "robot.yaml:5:39: geom: 'radius_m' does not apply to a box (it has size_m)");
}

TEST(RobotSpecTest, SyntaxErrorsKeepTheParsersLocation) {
  const std::string e = ErrorOf("name: tiny\nchassis: [\n");
  EXPECT_EQ(e.rfind("robot.yaml:3:1: ", 0), 0u) << e;
}

TEST(RobotSpecTest, DuplicateKeysAndNamesAreRefused) {
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "name: again\n"),
            "robot.yaml:6:1: duplicate key 'name' (first given at line 1)");
  EXPECT_EQ(ErrorOf(std::string(kTiny) +
                    "  bodies:\n"
                    "    - name: body\n"
                    "      joint: { name: j, type: ball }\n"
                    "      geoms: [{ type: sphere, radius_m: 0.01, mass_kg: 0.01 }]\n"),
            "robot.yaml:7:7: body name 'body' is already used at line 3");
}

// found by fuzz_robot: MJCF cannot carry a control character, so the world's body was another
TEST(RobotSpecTest, NamesWithControlCharactersAreRefused) {
  EXPECT_EQ(ErrorOf(TinyWith("name: body", "name: \"bo\\x01dy\"")),
            "robot.yaml:3:3: body name must not contain control characters (tab, newline, ...)");
  EXPECT_EQ(ErrorOf(TinyWith("name: tiny", "name: \"ti\\tny\"")),
            "robot.yaml:1:7: robot name must not contain control characters (tab, newline, ...)");
}

TEST(RobotSpecTest, ActuatorsMustNameAJoint) {
  EXPECT_EQ(ErrorOf(std::string(kTiny) + "actuators:\n  - { name: m, joint: axle }\n"),
            "robot.yaml:7:23: actuator 'm': no joint named 'axle'");
}

TEST(RobotSpecTest, ComponentsKeepTheirParametersForLaterValidation) {
  const RobotSpec robot = ParseRobotSpec(
      std::string(kTiny) +
          "components:\n  - { type: x.y, name: c, period_s: 0.03, params: { a: 1 } }\n",
      "robot.yaml");
  ASSERT_EQ(robot.components.size(), 1u);
  EXPECT_EQ(robot.components[0].type, "x.y");
  EXPECT_EQ(*robot.components[0].period_s, 0.03);
  EXPECT_TRUE(robot.components[0].params.IsMap());
  EXPECT_EQ(robot.components[0].location.line, 7);
}

TEST(RobotSpecTest, UnreadableFileSaysSo) {
  try {
    LoadRobotSpec("/nonexistent/robot.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/robot.yaml: cannot open file", 0), 0u);
  }
}

}  // namespace
}  // namespace unimouse
