// SPDX-License-Identifier: GPL-3.0-or-later
// How far a geom reaches along a direction, from its type, size and pose: the lowest point of
// a robot at rest, its width across a corridor.
#ifndef UNIMOUSE_CORE_GEOM_EXTENT_H_
#define UNIMOUSE_CORE_GEOM_EXTENT_H_

#include <mujoco/mujoco.h>

namespace unimouse {

/// Returns how far geom `geom` reaches from its centre along the unit vector `axis` (world
/// frame), from its size and its pose in `d` (after kinematics): its support distance. Spheres,
/// capsules, cylinders, boxes and ellipsoids; 0 for a plane, a height field or a mesh.
double GeomReach(const mjModel& m, const mjData& d, int geom, const double axis[3]);

/// Returns whether GeomReach knows the geom's shape.
bool HasReach(const mjModel& m, int geom);

/// Returns the width of the robot's colliding geoms across the world's x axis (the width of a
/// robot facing north), in metres; 0 when it has none GeomReach knows.
double WidthAcrossX(const mjModel& m, const mjData& d);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_GEOM_EXTENT_H_
