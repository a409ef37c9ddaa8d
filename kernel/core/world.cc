// SPDX-License-Identifier: GPL-3.0-or-later
#include "world.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <mutex>
#include <numbers>
#include <sstream>

#include "floor_grid.h"
#include "mujoco_guard.h"
#include "text_file.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

// geom groups: what rays and the renderer tell apart
constexpr int kGroupWorld = 0;  // floor, walls, obstacles
constexpr int kGroupRobot = 1;  // never seen by the robot's own sensors
constexpr int kGroupProxy = 3;  // collision stand-ins for scenery; invisible

// contact bits: static things touch robots, never each other
constexpr const char* kStaticContact = "contype='1' conaffinity='0'";
constexpr const char* kRobotContact = "contype='1' conaffinity='1'";

constexpr int kProxyCount = 8;
// proxies cover shapes this far beyond the robot's reach; they move every tick, and a robot
// crosses 1 cm in a 1 ms tick only at 10 m/s
constexpr double kProxyMargin_m = 0.01;
constexpr double kParkedZ_m = -10;
constexpr double kRestClearance_m = 1e-4;
constexpr size_t kSceneryChunkBoxes = 500;

class Mjcf {
 public:
  Mjcf() { out_ << std::setprecision(17); }
  template <class T>
  Mjcf& operator<<(const T& v) {
    out_ << v;
    return *this;
  }
  Mjcf& Vec(const Vec3& v) {
    out_ << v[0] << ' ' << v[1] << ' ' << v[2];
    return *this;
  }
  std::string str() const { return out_.str(); }

 private:
  std::ostringstream out_;
};

const char* MaterialOf(StaticBox::Kind kind) {
  switch (kind) {
    case StaticBox::Kind::kWall:
      return "wall";
    case StaticBox::Kind::kPost:
      return "post";
    case StaticBox::Kind::kObstacle:
      return "obstacle";
  }
  return "obstacle";
}

void WriteBoxGeom(Mjcf& x, const StaticBox& b, const char* contact, int group) {
  x << "<geom type='box' group='" << group << "' " << contact << " material='" << MaterialOf(b.kind)
    << "' pos='";
  x.Vec(b.center_m) << "' size='";
  x.Vec(b.half_m) << "' quat='" << std::cos(b.yaw_rad / 2) << " 0 0 " << std::sin(b.yaw_rad / 2)
                  << "'/>\n";
}

// the materials, in one order for every model (pictures draw the scenery's geoms with the
// physics model's materials, by index); the floor's texture only where there is a floor
void WriteAssets(Mjcf& x, bool floor_texture = true) {
  x << "<asset>\n";
  if (floor_texture) {
    x << "<texture name='grid' type='2d' builtin='checker' rgb1='0.12 0.12 0.12' "
         "rgb2='0.16 0.16 0.16' width='512' height='512'/>\n"
      << "<material name='floor' texture='grid' texrepeat='1 1' texuniform='true'/>\n";
  } else {
    x << "<material name='floor'/>\n";
  }
  x << "<material name='wall' rgba='0.92 0.92 0.9 1'/>\n"
    << "<material name='post' rgba='0.85 0.15 0.1 1'/>\n"
    << "<material name='obstacle' rgba='0.3 0.5 0.8 1'/>\n"
    << "</asset>\n";
}

void WriteGeom(Mjcf& x, const GeomSpec& g, const std::string& prefix) {
  x << "<geom";
  if (!g.name.empty()) x << " name='" << XmlEscaped(prefix + g.name) << "'";
  x << " type='" << g.type << "' group='" << kGroupRobot << "' ";
  x << (g.contact ? kRobotContact : "contype='0' conaffinity='0'");
  if (g.type == "box") {
    x << " size='" << g.size_m[0] / 2 << ' ' << g.size_m[1] / 2 << ' ' << g.size_m[2] / 2 << "'";
  } else if (g.type == "sphere") {
    x << " size='" << g.radius_m << "'";
  } else {
    x << " size='" << g.radius_m << ' ' << g.length_m / 2 << "'";
  }
  x << " pos='";
  x.Vec(g.pos_m) << "' euler='";
  x.Vec(g.euler_deg) << "' mass='" << g.mass_kg << "' friction='" << g.friction
                     << " 0.005 0.0001' rgba='" << g.rgba[0] << ' ' << g.rgba[1] << ' ' << g.rgba[2]
                     << ' ' << g.rgba[3] << "'/>\n";
}

// a robot's bodies; every name it brings into the model starts with `prefix`
void WriteBody(Mjcf& x, const BodySpec& b, bool is_chassis, const std::string& prefix) {
  x << "<body name='" << XmlEscaped(prefix + b.name) << "'";
  if (!is_chassis) {
    x << " pos='";
    x.Vec(b.pos_m) << "' euler='";
    x.Vec(b.euler_deg) << "'";
  }
  x << ">\n";
  if (is_chassis) {
    x << "<freejoint name='" << XmlEscaped(prefix + b.name) << "_free'/>\n";
  } else {
    const JointSpec& j = *b.joint;
    x << "<joint name='" << XmlEscaped(prefix + j.name) << "' type='" << j.type << "'";
    if (j.type == "hinge") {
      x << " axis='";
      x.Vec(j.axis) << "'";
    }
    x << " damping='" << j.damping_nm_s << "' armature='" << j.armature_kg_m2 << "'/>\n";
  }
  for (const auto& g : b.geoms) WriteGeom(x, g, prefix);
  for (const auto& s : b.sites) {
    x << "<site name='" << XmlEscaped(prefix + s.name) << "' group='" << kGroupRobot
      << "' size='0.003' pos='";
    x.Vec(s.pos_m) << "' euler='";
    x.Vec(s.euler_deg) << "'/>\n";
  }
  for (const auto& child : b.bodies) WriteBody(x, child, false, prefix);
  x << "</body>\n";
}

// distance on the floor plane from a point to a box yawed by the angle of `cos_sin`
double FloorDistance(const StaticBox& b, const std::array<double, 2>& cos_sin, double px,
                     double py) {
  const double dx = px - b.center_m[0];
  const double dy = py - b.center_m[1];
  const double c = cos_sin[0], s = cos_sin[1];
  const double lx = std::max(std::fabs(c * dx + s * dy) - b.half_m[0], 0.0);
  const double ly = std::max(std::fabs(-s * dx + c * dy) - b.half_m[1], 0.0);
  return std::hypot(lx, ly);
}

// a box's footprint on the floor as an axis-aligned rectangle
FloorRect Footprint(const StaticBox& b) {
  const double c = std::fabs(std::cos(b.yaw_rad)), s = std::fabs(std::sin(b.yaw_rad));
  const double hx = c * b.half_m[0] + s * b.half_m[1], hy = s * b.half_m[0] + c * b.half_m[1];
  return {b.center_m[0] - hx, b.center_m[1] - hy, b.center_m[0] + hx, b.center_m[1] + hy};
}

FloorGrid IndexOf(const std::vector<StaticBox>& boxes, double square_m) {
  std::vector<FloorRect> footprints;
  footprints.reserve(boxes.size());
  for (const StaticBox& b : boxes) footprints.push_back(Footprint(b));
  return FloorGrid(footprints, square_m);
}

// how far a geom reaches below its centre, from its orientation
double ReachBelow(const mjModel& m, const mjData& d, int g) {
  const mjtNum* size = m.geom_size + 3 * g;
  const mjtNum* r = d.geom_xmat + 9 * g;  // row-major; row 2 holds each axis's world z
  switch (m.geom_type[g]) {
    case mjGEOM_SPHERE:
      return size[0];
    case mjGEOM_CAPSULE:
      return size[0] + size[1] * std::fabs(r[8]);
    case mjGEOM_CYLINDER:
      return size[0] * std::sqrt(std::max(0.0, 1 - r[8] * r[8])) + size[1] * std::fabs(r[8]);
    case mjGEOM_BOX:
      return size[0] * std::fabs(r[6]) + size[1] * std::fabs(r[7]) + size[2] * std::fabs(r[8]);
    default:
      return m.geom_rbound[g];
  }
}

// MuJoCo 2.2.2's broadphase, run at every step to sort a handful of bodies, costs about a
// twentieth of a step here (mostly a 3 x 3 eigendecomposition of the robot geoms' spread). The
// geom pairs it can hand to the narrow phase are known once the model is: every pair of geoms
// in different bodies that its contact filter lets through, in the order of their bodies' ids.
// Given those as predefined pairs, in that order and with the parameters it would mix for them,
// mj_collision runs the same narrow phase on the same pairs, whose bounding spheres drop every
// pair the broadphase would have skipped, and lists the same contacts in the same order.
std::vector<std::array<int, 2>> CollidableGeomPairs(const mjModel& m) {
  const bool filter_parent = (m.opt.disableflags & mjDSBL_FILTERPARENT) == 0;
  auto weld_parent = [&](int weld) { return m.body_weldid[m.body_parentid[weld]]; };
  std::vector<std::array<int, 2>> pairs;
  for (int b1 = 0; b1 < m.nbody; ++b1) {
    for (int b2 = b1 + 1; b2 < m.nbody; ++b2) {
      const int weld1 = m.body_weldid[b1], weld2 = m.body_weldid[b2];
      if (weld1 == weld2) continue;
      if (filter_parent && weld1 != 0 && weld2 != 0 &&
          (weld1 == weld_parent(weld2) || weld2 == weld_parent(weld1))) {
        continue;
      }
      for (int g1 = m.body_geomadr[b1]; g1 < m.body_geomadr[b1] + m.body_geomnum[b1]; ++g1) {
        for (int g2 = m.body_geomadr[b2]; g2 < m.body_geomadr[b2] + m.body_geomnum[b2]; ++g2) {
          if ((m.geom_contype[g1] & m.geom_conaffinity[g2]) != 0 ||
              (m.geom_contype[g2] & m.geom_conaffinity[g1]) != 0) {
            pairs.push_back({g1, g2});
          }
        }
      }
    }
  }
  return pairs;
}

// what mj_collideGeoms mixes for a pair of geoms it found itself (MuJoCo 2.2.2), with the same
// operations in the same order, so that the pair's contacts are the same to the bit
void MixPairParameters(mjModel& m, int pair, int g1, int g2) {
  m.pair_geom1[pair] = g1;
  m.pair_geom2[pair] = g2;
  m.pair_signature[pair] = ((m.geom_bodyid[g1] + 1) << 16) + m.geom_bodyid[g2] + 1;
  if (m.geom_type[g1] > m.geom_type[g2]) std::swap(g1, g2);  // as it orders them
  m.pair_margin[pair] = std::max(m.geom_margin[g1], m.geom_margin[g2]);
  m.pair_gap[pair] = std::max(m.geom_gap[g1], m.geom_gap[g2]);
  mjtNum friction[3], solref[mjNREF], solimp[mjNIMP];
  if (m.geom_priority[g1] != m.geom_priority[g2]) {
    const int g = m.geom_priority[g1] > m.geom_priority[g2] ? g1 : g2;
    m.pair_dim[pair] = m.geom_condim[g];
    std::copy_n(m.geom_friction + 3 * g, 3, friction);
    std::copy_n(m.geom_solref + mjNREF * g, mjNREF, solref);
    std::copy_n(m.geom_solimp + mjNIMP * g, mjNIMP, solimp);
  } else {
    m.pair_dim[pair] = std::max(m.geom_condim[g1], m.geom_condim[g2]);
    for (int i = 0; i < 3; ++i) {
      friction[i] = std::max(m.geom_friction[3 * g1 + i], m.geom_friction[3 * g2 + i]);
    }
    const mjtNum mix1 = m.geom_solmix[g1], mix2 = m.geom_solmix[g2];
    mjtNum mix = 1.0;
    if (mix1 >= mjMINVAL && mix2 >= mjMINVAL) {
      mix = mix1 / (mix1 + mix2);
    } else if (mix1 < mjMINVAL && mix2 < mjMINVAL) {
      mix = 0.5;
    } else if (mix1 < mjMINVAL) {
      mix = 0.0;
    }
    const mjtNum* ref1 = m.geom_solref + mjNREF * g1;
    const mjtNum* ref2 = m.geom_solref + mjNREF * g2;
    for (int i = 0; i < mjNREF; ++i) {
      solref[i] = ref1[0] > 0 && ref2[0] > 0 ? mix * ref1[i] + (1 - mix) * ref2[i]
                                             : std::min(ref1[i], ref2[i]);
    }
    for (int i = 0; i < mjNIMP; ++i) {
      solimp[i] = m.geom_solimp[mjNIMP * g1 + i] * mix;
      solimp[i] += m.geom_solimp[mjNIMP * g2 + i] * (1 - mix);
    }
  }
  const mjtNum unpacked[5] = {friction[0], friction[0], friction[1], friction[2], friction[2]};
  std::copy_n(unpacked, 5, m.pair_friction + 5 * pair);
  std::copy_n(solref, mjNREF, m.pair_solref + mjNREF * pair);
  std::copy_n(solimp, mjNIMP, m.pair_solimp + mjNIMP * pair);
}

}  // namespace

mjModel* CompileMjcf(const std::string& mjcf, const std::string& what) {
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* name = "world.xml";
  UNIMOUSE_DEMAND(mj_makeEmptyFileVFS(&vfs, name, static_cast<int>(mjcf.size())) == 0);
  const int index = mj_findFileVFS(&vfs, name);
  std::memcpy(vfs.filedata[index], mjcf.data(), mjcf.size());
  char error[1024] = "";
  mjModel* m = nullptr;
  {
    // MuJoCo's XML loader keeps global state; a fit builds its replays' worlds on several
    // threads at once (kernel/fit/fit.cc), so one at a time
    static std::mutex loading;
    const std::lock_guard<std::mutex> one_at_a_time(loading);
    GuardMujoco([&] { m = mj_loadXML(name, &vfs, error, sizeof(error)); });
  }
  mj_deleteVFS(&vfs);
  if (m == nullptr) {
    std::string reason(error);
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(what + ": MuJoCo cannot build it: " + reason);
  }
  return m;
}

std::vector<StaticBox> MazeBoxes(const Maze& maze) {
  const MazeDimensions& dims = maze.dimensions();
  const double p = dims.cell_m;
  const double t = dims.wall_thickness_m / 2;
  const double h = dims.wall_height_m / 2;
  const double half_wall = (dims.cell_m - dims.wall_thickness_m) / 2;
  std::vector<StaticBox> boxes;
  for (int y = 0; y <= maze.height(); ++y) {
    for (int x = 0; x <= maze.width(); ++x) {
      boxes.push_back({StaticBox::Kind::kPost, {p * x, p * y, h}, {t, t, h}, 0});
    }
  }
  for (int y = 0; y <= maze.height(); ++y) {
    for (int x = 0; x < maze.width(); ++x) {
      if (maze.HasHorizontalWall(x, y)) {
        boxes.push_back({StaticBox::Kind::kWall, {p * (x + 0.5), p * y, h}, {half_wall, t, h}, 0});
      }
    }
  }
  for (int y = 0; y < maze.height(); ++y) {
    for (int x = 0; x <= maze.width(); ++x) {
      if (maze.HasVerticalWall(x, y)) {
        boxes.push_back({StaticBox::Kind::kWall, {p * x, p * (y + 0.5), h}, {t, half_wall, h}, 0});
      }
    }
  }
  return boxes;
}

std::vector<StaticBox> MazeCollisionBoxes(const Maze& maze) {
  const MazeDimensions& dims = maze.dimensions();
  const double p = dims.cell_m;
  const double t = dims.wall_thickness_m / 2;
  const double h = dims.wall_height_m / 2;
  const int w = maze.width(), ht = maze.height();
  std::vector<StaticBox> boxes;
  std::vector<char> post_used(static_cast<size_t>((w + 1) * (ht + 1)), 0);
  auto use_post = [&](int x, int y) { post_used[static_cast<size_t>(y * (w + 1) + x)] = 1; };

  // east-west runs, posts included at both ends
  for (int y = 0; y <= ht; ++y) {
    for (int x = 0; x < w;) {
      if (!maze.HasHorizontalWall(x, y)) {
        ++x;
        continue;
      }
      const int begin = x;
      while (x < w && maze.HasHorizontalWall(x, y)) use_post(x++, y);
      use_post(x, y);
      boxes.push_back({StaticBox::Kind::kWall,
                       {p * (begin + x) / 2, p * y, h},
                       {p * (x - begin) / 2 + t, t, h},
                       0});
    }
  }
  // north-south runs
  for (int x = 0; x <= w; ++x) {
    for (int y = 0; y < ht;) {
      if (!maze.HasVerticalWall(x, y)) {
        ++y;
        continue;
      }
      const int begin = y;
      while (y < ht && maze.HasVerticalWall(x, y)) use_post(x, y++);
      use_post(x, y);
      boxes.push_back({StaticBox::Kind::kWall,
                       {p * x, p * (begin + y) / 2, h},
                       {t, p * (y - begin) / 2 + t, h},
                       0});
    }
  }
  for (int y = 0; y <= ht; ++y) {
    for (int x = 0; x <= w; ++x) {
      if (!post_used[static_cast<size_t>(y * (w + 1) + x)]) {
        boxes.push_back({StaticBox::Kind::kPost, {p * x, p * y, h}, {t, t, h}, 0});
      }
    }
  }
  return boxes;
}

Pose2D CellCentre(Cell c, Heading h, const MazeDimensions& dims) {
  return {dims.cell_m * (c.x + 0.5), dims.cell_m * (c.y + 0.5), HeadingYaw(h)};
}

Cell CellAt(double x_m, double y_m, const MazeDimensions& dims) {
  return {static_cast<int>(std::floor(x_m / dims.cell_m)),
          static_cast<int>(std::floor(y_m / dims.cell_m))};
}

World::~World() = default;

std::unique_ptr<World> World::Build(const RobotSpec& robot, const Maze* maze,
                                    std::optional<Pose2D> spawn,
                                    const std::vector<StaticBox>& boxes) {
  return Build({WorldRobot{&robot, "", spawn}}, maze, boxes);
}

std::unique_ptr<World> World::Build(const std::vector<WorldRobot>& robots, const Maze* maze,
                                    const std::vector<StaticBox>& boxes) {
  UNIMOUSE_DEMAND(!robots.empty());
  const RobotSpec& robot = *robots.front().spec;
  std::unique_ptr<World> w(new World());
  Pose2D default_spawn;
  double floor_centre_x = 0, floor_centre_y = 0, floor_half_m = 5;
  if (maze != nullptr) {
    if (maze->width() > kMaxMazeSide_cells || maze->height() > kMaxMazeSide_cells) {
      throw InputError("a " + std::to_string(maze->width()) + " x " +
                       std::to_string(maze->height()) + " maze is larger than the " +
                       std::to_string(kMaxMazeSide_cells) + " x " +
                       std::to_string(kMaxMazeSide_cells) +
                       " cells a run builds (docs/limits.md); the maze tools read larger ones");
    }
    w->maze_ = *maze;
    const MazeDimensions& dims = maze->dimensions();
    w->scenery_ = MazeBoxes(*maze);
    w->collision_shapes_ = MazeCollisionBoxes(*maze);
    floor_centre_x = dims.cell_m * maze->width() / 2;
    floor_centre_y = dims.cell_m * maze->height() / 2;
    floor_half_m = dims.cell_m * std::max(maze->width(), maze->height()) / 2 + 0.5;
    default_spawn = CellCentre(maze->start(), maze->start_heading(), dims);
  } else {
    default_spawn = {0, 0, std::numbers::pi / 2};
  }
  w->robots_.resize(robots.size());
  for (size_t i = 0; i < robots.size(); ++i) {
    w->robots_[i].spawn = robots[i].spawn.value_or(default_spawn);
  }
  for (const StaticBox& b : boxes) {
    w->scenery_.push_back(b);
    w->collision_shapes_.push_back(b);
    const double reach = std::max(std::fabs(b.center_m[0] - floor_centre_x),
                                  std::fabs(b.center_m[1] - floor_centre_y)) +
                         std::hypot(b.half_m[0], b.half_m[1]) + 0.5;
    floor_half_m = std::max(floor_half_m, reach);
  }

  // the proxies look for shapes near the robot at every step, and rays for walls along their
  // way: both through an index of squares a maze cell wide, and the shapes' axes worked out once
  for (const StaticBox& b : w->collision_shapes_) {
    w->shape_cos_sin_.push_back({std::cos(b.yaw_rad), std::sin(b.yaw_rad)});
  }
  const double square_m = maze != nullptr ? maze->dimensions().cell_m : MazeDimensions{}.cell_m;
  w->collision_grid_ = IndexOf(w->collision_shapes_, square_m);
  w->scenery_grid_ = IndexOf(w->scenery_, square_m);

  // physics: floor, proxies, robot
  Mjcf x;
  x << "<mujoco model='" << XmlEscaped(robot.name) << "'>\n"
    << "<compiler angle='degree' eulerseq='xyz' autolimits='true'/>\n"
    << "<option timestep='" << robot.timestep_s << "' integrator='" << robot.integrator << "'/>\n"
    << "<visual><global offwidth='1920' offheight='1080'/></visual>\n";
  WriteAssets(x);
  x << "<worldbody>\n"
    << "<light name='sun' directional='true' pos='0 0 4' dir='0 0 -1'/>\n"
    << "<geom name='floor' type='plane' group='" << kGroupWorld << "' " << kStaticContact
    << " material='floor' friction='0.1 0.005 0.0001' pos='" << floor_centre_x << ' '
    << floor_centre_y << " 0' size='" << floor_half_m << ' ' << floor_half_m << " 0.05'/>\n";
  const int proxies =
      w->collision_shapes_.empty() ? 0 : kProxyCount * static_cast<int>(robots.size());
  for (int i = 0; i < proxies; ++i) {
    x << "<geom name='proxy" << i << "' type='box' group='" << kGroupProxy << "' " << kStaticContact
      << " friction='0.6 0.005 0.0001' pos='0 0 " << kParkedZ_m
      << "' size='0.01 0.01 0.01' rgba='1 0 1 0.3'/>\n";
  }
  for (const WorldRobot& r : robots) WriteBody(x, r.spec->chassis, true, r.prefix);
  x << "</worldbody>\n<actuator>\n";
  for (const WorldRobot& r : robots) {
    for (const auto& a : r.spec->actuators) {
      x << "<motor name='" << XmlEscaped(r.prefix + a.name) << "' joint='"
        << XmlEscaped(r.prefix + a.joint) << "' gear='1'/>\n";
    }
  }
  x << "</actuator>\n</mujoco>\n";
  w->mjcf_ = x.str();
  w->model_.reset(CompileMjcf(w->mjcf_, robot.file));
  // the same model again with room for its collidable pairs, which then take the broadphase's
  // place (CollidableGeomPairs); the compiler sorts <pair> elements, so they are written after
  UNIMOUSE_DEMAND(w->model_->nexclude == 0);  // the broadphase would skip excluded bodies
  const std::vector<std::array<int, 2>> pairs = CollidableGeomPairs(*w->model_);
  if (!pairs.empty()) {
    std::string with_pairs = w->mjcf_;
    std::string room = "<contact>\n";
    for (size_t i = 0; i < pairs.size(); ++i) room += "<pair geom1='floor' geom2='floor'/>\n";
    with_pairs.insert(with_pairs.rfind("</mujoco>"), room + "</contact>\n");
    w->model_.reset(CompileMjcf(with_pairs, robot.file));
    mjModel& m = *w->model_;
    UNIMOUSE_DEMAND(m.npair == static_cast<int>(pairs.size()));
    for (int i = 0; i < m.npair; ++i) MixPairParameters(m, i, pairs[i][0], pairs[i][1]);
    m.opt.collision = mjCOL_PAIR;
  }

  const mjModel& m = *w->model_;
  w->proxy_count_ = proxies;
  w->first_proxy_ = proxies > 0 ? mj_name2id(&m, mjOBJ_GEOM, "proxy0") : -1;
  w->proxy_shape_.assign(static_cast<size_t>(proxies), -1);
  for (size_t i = 0; i < robots.size(); ++i) {
    RobotSlot& slot = w->robots_[i];
    const RobotSpec& spec = *robots[i].spec;
    slot.body = mj_name2id(&m, mjOBJ_BODY, (robots[i].prefix + spec.chassis.name).c_str());
    UNIMOUSE_DEMAND(slot.body > 0);
    const int free_joint = m.body_jntadr[slot.body];
    slot.qpos = m.jnt_qposadr[free_joint];
    slot.qvel = m.jnt_dofadr[free_joint];

    // find the resting height and reach of the robot from its geometry: lift it to 1 m, then see
    // how far its lowest contact geom hangs below and how far any geom sticks out sideways
    std::unique_ptr<mjData, DataDeleter> d;
    GuardMujoco([&] { d.reset(mj_makeData(&m)); });
    d->qpos[slot.qpos + 2] = 1;
    GuardMujoco([&] { mj_kinematics(&m, d.get()); });
    double lowest = std::numeric_limits<double>::infinity();
    double reach = 0;
    for (int g = 0; g < m.ngeom; ++g) {
      if (m.body_rootid[m.geom_bodyid[g]] != slot.body) continue;
      slot.geoms.push_back(g);
      const mjtNum* gp = d->geom_xpos + 3 * g;
      reach = std::max(reach, std::hypot(gp[0], gp[1]) + m.geom_rbound[g]);
      if (m.geom_contype[g] != 0) lowest = std::min(lowest, gp[2] - ReachBelow(m, *d, g));
    }
    if (!std::isfinite(lowest)) {
      throw InputError(spec.chassis.location.ToString() +
                       ": the robot has no geom with contact: true, so it would fall through the "
                       "floor");
    }
    slot.rest_height_m = 1 - lowest + kRestClearance_m;
    slot.radius_m = reach;
  }

  // scenery: every static box, for rays and pictures, in models of a few hundred boxes each:
  // MuJoCo's compiler takes time that grows with the square of a model's geoms (38 s for the
  // 33 000 boxes of a 128 x 128 maze in one model), and linearly over pieces
  for (size_t first = 0; first < w->scenery_.size(); first += kSceneryChunkBoxes) {
    const size_t end = std::min(w->scenery_.size(), first + kSceneryChunkBoxes);
    Mjcf s;
    s << "<mujoco model='scenery'>\n";
    WriteAssets(s, /*floor_texture=*/false);
    s << "<worldbody>\n";
    for (size_t i = first; i < end; ++i) {
      WriteBoxGeom(s, w->scenery_[i], "contype='0' conaffinity='0'", kGroupWorld);
    }
    s << "</worldbody>\n</mujoco>\n";
    SceneryChunk chunk;
    chunk.model.reset(CompileMjcf(s.str(), "scenery"));
    GuardMujoco([&] { chunk.data.reset(mj_makeData(chunk.model.get())); });
    GuardMujoco([&] { mj_kinematics(chunk.model.get(), chunk.data.get()); });
    // what a ray cast tests of each box, as MuJoCo placed it
    const mjModel& cm = *chunk.model;
    const mjData& cd = *chunk.data;
    for (int g = 0; g < cm.ngeom; ++g) {
      RayBox box;
      std::copy_n(cd.geom_xpos + 3 * g, 3, box.pos);
      std::copy_n(cd.geom_xmat + 9 * g, 9, box.mat);
      std::copy_n(cm.geom_size + 3 * g, 3, box.size);
      w->ray_boxes_.push_back(box);
    }
    w->scenery_chunks_.push_back(std::move(chunk));
  }
  return w;
}

int World::RobotOfBody(int body) const {
  if (body <= 0) return -1;
  const int root = model_->body_rootid[body];
  for (size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i].body == root) return static_cast<int>(i);
  }
  return -1;
}

void World::PlaceRobot(mjData& d, const Pose2D& pose, int robot) const {
  const RobotSlot& slot = robots_[robot];
  mjtNum* q = d.qpos + slot.qpos;
  q[0] = pose.x_m;
  q[1] = pose.y_m;
  q[2] = slot.rest_height_m;
  q[3] = std::cos(pose.yaw_rad / 2);
  q[4] = 0;
  q[5] = 0;
  q[6] = std::sin(pose.yaw_rad / 2);
  for (int i = 0; i < 6; ++i) d.qvel[slot.qvel + i] = 0;
}

Pose2D World::RobotPose(const mjData& d, int robot) const {
  const mjtNum* q = d.qpos + robots_[robot].qpos;
  // heading of the body's x axis projected on the floor
  const double yaw =
      std::atan2(2 * (q[3] * q[6] + q[4] * q[5]), 1 - 2 * (q[5] * q[5] + q[6] * q[6]));
  return {q[0], q[1], yaw};
}

void World::UpdateCollisionProxies(const mjData& d) {
  if (proxy_count_ == 0) return;
  for (size_t robot = 0; robot < robots_.size(); ++robot) {
    UpdateProxiesOf(d, static_cast<int>(robot));
  }
}

void World::UpdateProxiesOf(const mjData& d, int robot) {
  const RobotSlot& r = robots_[robot];
  const mjtNum* p = d.qpos + r.qpos;
  const double reach = r.radius_m + kProxyMargin_m;

  // the shapes within reach, in index order: those of the squares around the robot, filtered
  near_.clear();
  collision_grid_.ShapesNear({p[0] - reach, p[1] - reach, p[0] + reach, p[1] + reach}, near_);
  candidates_.clear();
  for (const int i : near_) {
    if (FloorDistance(collision_shapes_[i], shape_cos_sin_[i], p[0], p[1]) < reach) {
      candidates_.push_back(i);
    }
  }
  if (static_cast<int>(candidates_.size()) > kProxyCount) {
    // keep the nearest; ties by index keep it deterministic
    std::sort(candidates_.begin(), candidates_.end(), [&](int a, int b) {
      const double da = FloorDistance(collision_shapes_[a], shape_cos_sin_[a], p[0], p[1]);
      const double db = FloorDistance(collision_shapes_[b], shape_cos_sin_[b], p[0], p[1]);
      return da != db ? da < db : a < b;
    });
    candidates_.resize(static_cast<size_t>(kProxyCount));
    std::sort(candidates_.begin(), candidates_.end());
    ++proxy_overflows_;
  }

  mjModel& m = *model_;
  for (int own = 0; own < kProxyCount; ++own) {
    const int slot = robot * kProxyCount + own;
    const int shape = own < static_cast<int>(candidates_.size()) ? candidates_[own] : -1;
    if (shape < 0 && proxy_shape_[slot] < 0) continue;
    proxy_shape_[slot] = shape;
    const int g = first_proxy_ + slot;
    if (shape < 0) {
      m.geom_pos[3 * g + 0] = 0;
      m.geom_pos[3 * g + 1] = 0;
      m.geom_pos[3 * g + 2] = kParkedZ_m;
      continue;
    }
    // clip axis-aligned runs to a window around the robot: a proxy with a small bounding
    // sphere lets MuJoCo skip the narrow phase against the robot's far parts
    StaticBox b = collision_shapes_[shape];
    if (b.yaw_rad == 0) {
      for (int k = 0; k < 2; ++k) {
        const double lo = std::max(b.center_m[k] - b.half_m[k], p[k] - reach);
        const double hi = std::min(b.center_m[k] + b.half_m[k], p[k] + reach);
        b.center_m[k] = (lo + hi) / 2;
        b.half_m[k] = (hi - lo) / 2;
      }
    }
    for (int k = 0; k < 3; ++k) {
      m.geom_pos[3 * g + k] = b.center_m[k];
      m.geom_size[3 * g + k] = b.half_m[k];
    }
    m.geom_quat[4 * g + 0] = std::cos(b.yaw_rad / 2);
    m.geom_quat[4 * g + 1] = 0;
    m.geom_quat[4 * g + 2] = 0;
    m.geom_quat[4 * g + 3] = std::sin(b.yaw_rad / 2);
    m.geom_rbound[g] = std::hypot(b.half_m[0], b.half_m[1], b.half_m[2]);
  }
}

bool World::RobotTouchesScenery(const mjData& d, int robot, int* contact) const {
  const mjModel& m = *model_;
  const int body = robots_[robot].body;
  if (contact != nullptr) *contact = -1;
  for (int i = 0; i < d.ncon; ++i) {
    const mjContact& c = d.contact[i];
    const bool proxy1 = c.geom1 >= first_proxy_ && c.geom1 < first_proxy_ + proxy_count_;
    const bool proxy2 = c.geom2 >= first_proxy_ && c.geom2 < first_proxy_ + proxy_count_;
    if (proxy1 == proxy2 || c.dist > 0) continue;
    const int other = proxy1 ? c.geom2 : c.geom1;
    if (m.body_rootid[m.geom_bodyid[other]] != body) continue;
    if (contact != nullptr) *contact = i;
    return true;
  }
  return false;
}

int World::RobotTouchesRobot(const mjData& d, int robot, int* contact) const {
  const mjModel& m = *model_;
  int touched = -1;
  if (contact != nullptr) *contact = -1;
  for (int i = 0; i < d.ncon && robots_.size() > 1; ++i) {
    const mjContact& c = d.contact[i];
    if (c.dist > 0) continue;
    const int a = RobotOfBody(m.geom_bodyid[c.geom1]);
    const int b = RobotOfBody(m.geom_bodyid[c.geom2]);
    if (a < 0 || b < 0 || a == b || (a != robot && b != robot)) continue;
    const int other = a == robot ? b : a;
    if (touched >= 0 && other >= touched) continue;
    touched = other;
    if (contact != nullptr) *contact = i;
  }
  return touched;
}

double World::CastRay(const mjData& d, const double origin[3], const double direction[3],
                      double max_m, int from) const {
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(origin[k]) || !std::isfinite(direction[k])) return -1;
  }
  if (!std::isfinite(max_m)) return -1;
  const mjtByte world_only[mjNGROUP] = {1, 0, 0, 0, 0, 0};
  int geom = -1;
  double best = -1;
  GuardMujoco(
      [&] { best = mj_ray(model_.get(), &d, origin, direction, world_only, 1, -1, &geom); });
  // the walls along the ray's way on the floor, each tested as MuJoCo's ray cast tests a geom:
  // the nearest of them is the nearest of all
  ray_shapes_.clear();
  scenery_grid_.ShapesAlong(origin[0], origin[1], direction[0], direction[1],
                            max_m * std::hypot(direction[0], direction[1]), ray_shapes_);
  for (const int i : ray_shapes_) {
    const RayBox& b = ray_boxes_[static_cast<size_t>(i)];
    const double wall = mju_rayGeom(b.pos, b.mat, b.size, origin, direction, mjGEOM_BOX);
    if (wall >= 0 && (best < 0 || wall < best)) best = wall;
  }
  // other robots are surfaces too: each one whose reach the ray's line passes near, geom by geom
  const mjModel& m = *model_;
  for (size_t r = 0; r < robots_.size() && robots_.size() > 1; ++r) {
    if (static_cast<int>(r) == from) continue;
    const RobotSlot& slot = robots_[r];
    const mjtNum* c = d.qpos + slot.qpos;
    const double to[3] = {c[0] - origin[0], c[1] - origin[1], c[2] - origin[2]};
    const double along = mju_dot3(to, direction) / mju_dot3(direction, direction);
    double off[3];
    for (int k = 0; k < 3; ++k) off[k] = to[k] - along * direction[k];
    if (mju_norm3(off) > slot.radius_m + 0.1) continue;
    for (const int g : slot.geoms) {
      const double hit = mju_rayGeom(d.geom_xpos + 3 * g, d.geom_xmat + 9 * g, m.geom_size + 3 * g,
                                     origin, direction, m.geom_type[g]);
      if (hit >= 0 && (best < 0 || hit < best)) best = hit;
    }
  }
  return best >= 0 && best <= max_m ? best : -1;
}

}  // namespace unimouse
