// SPDX-License-Identifier: GPL-3.0-or-later
#include "geom_extent.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unimouse {

bool HasReach(const mjModel& m, int geom) {
  switch (m.geom_type[geom]) {
    case mjGEOM_SPHERE:
    case mjGEOM_CAPSULE:
    case mjGEOM_CYLINDER:
    case mjGEOM_BOX:
    case mjGEOM_ELLIPSOID:
      return true;
    default:
      return false;
  }
}

double GeomReach(const mjModel& m, const mjData& d, int geom, const double axis[3]) {
  const double* r = d.geom_xmat + 9 * geom;  // row-major: the geom's own axes are its columns
  const double* size = m.geom_size + 3 * geom;
  double c[3];
  for (int j = 0; j < 3; ++j) {
    c[j] = std::abs(axis[0] * r[j] + axis[1] * r[3 + j] + axis[2] * r[6 + j]);
  }
  switch (m.geom_type[geom]) {
    case mjGEOM_SPHERE:
      return size[0];
    case mjGEOM_CAPSULE:
      return size[0] + c[2] * size[1];
    case mjGEOM_CYLINDER:
      return c[2] * size[1] + size[0] * std::sqrt(std::max(0.0, 1 - c[2] * c[2]));
    case mjGEOM_BOX:
      return c[0] * size[0] + c[1] * size[1] + c[2] * size[2];
    case mjGEOM_ELLIPSOID:
      return std::sqrt(std::pow(c[0] * size[0], 2) + std::pow(c[1] * size[1], 2) +
                       std::pow(c[2] * size[2], 2));
    default:
      return 0;
  }
}

double WidthAcrossX(const mjModel& m, const mjData& d) {
  constexpr double kX[3] = {1, 0, 0};
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int g = 0; g < m.ngeom; ++g) {
    // the world's own geoms (floor, walls) are body 0; a geom that collides with nothing is a
    // picture only
    if (m.geom_bodyid[g] == 0 || !HasReach(m, g)) continue;
    if (m.geom_contype[g] == 0 && m.geom_conaffinity[g] == 0) continue;
    const double reach = GeomReach(m, d, g, kX);
    low = std::min(low, d.geom_xpos[3 * g] - reach);
    high = std::max(high, d.geom_xpos[3 * g] + reach);
  }
  return high > low ? high - low : 0;
}

}  // namespace unimouse
