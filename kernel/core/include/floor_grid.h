// SPDX-License-Identifier: GPL-3.0-or-later
// An index of shapes standing on the floor: a grid of equal squares, each listing the shapes
// whose footprint reaches into it. A query near the robot (the collision proxies, a sensor's
// ray) then visits the few squares around it instead of every wall of the maze, so a step costs
// the same in a 16 x 16 maze as in a 128 x 128 one.
#ifndef UNIMOUSE_CORE_FLOOR_GRID_H_
#define UNIMOUSE_CORE_FLOOR_GRID_H_

#include <cstdint>
#include <vector>

namespace unimouse {

/// A shape's footprint on the floor, as an axis-aligned rectangle.
struct FloorRect {
  double x0_m, y0_m, x1_m, y1_m;
};

/// Shapes on the floor, indexed by the squares of a grid their footprints reach into.
class FloorGrid {
 public:
  /// Indexes `footprints` (shape i has footprints[i]) in squares of about `square_m`; the grid
  /// covers them all, and grows its squares rather than hold more than about a million.
  FloorGrid(const std::vector<FloorRect>& footprints, double square_m);
  /// An index of no shape.
  FloorGrid() = default;

  /// Appends to `out`, in ascending order and once each, the shapes whose footprint reaches
  /// into a square the rectangle overlaps: every shape within the rectangle, and a few near it.
  void ShapesNear(const FloorRect& area, std::vector<int>& out) const;
  /// Appends to `out`, once each, the shapes in the squares a segment crosses on the floor, from
  /// (x, y) along (dx, dy) for `length_m` (dx, dy a direction of any length; (0, 0) is the
  /// square of the point alone): every shape the segment meets, and a few near it. A segment
  /// with a coordinate that is not finite meets none.
  void ShapesAlong(double x_m, double y_m, double dx, double dy, double length_m,
                   std::vector<int>& out) const;

  /// Returns the rectangle the grid covers (empty when it indexes nothing) and its squares' side.
  FloorRect bounds() const {
    return {x0_m_, y0_m_, x0_m_ + nx_ * square_m_, y0_m_ + ny_ * square_m_};
  }
  double square_m() const { return square_m_; }

 private:
  void AddSquare(int ix, int iy, std::vector<int>& out) const;
  // starts a query: no shape is listed yet
  void NewQuery() const;

  double x0_m_ = 0, y0_m_ = 0, square_m_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> first_;   // per square, where its shapes begin in shapes_ (nx*ny + 1 entries)
  std::vector<int> shapes_;  // shape indices, square after square
  // a stamp per shape, so that a query lists each once without a set
  mutable std::vector<uint32_t> seen_;
  mutable uint32_t stamp_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_FLOOR_GRID_H_
