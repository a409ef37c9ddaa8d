// SPDX-License-Identifier: GPL-3.0-or-later
#include "floor_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unimouse {
namespace {

// a footprint grows by this much in the index, so that a query touching a square's edge or
// corner exactly still finds the shapes of the squares beside it
constexpr double kPad_m = 1e-3;
constexpr double kMaxSquares = 1 << 20;

}  // namespace

FloorGrid::FloorGrid(const std::vector<FloorRect>& footprints, double square_m) {
  if (footprints.empty()) return;
  double x1 = -std::numeric_limits<double>::infinity(), y1 = x1;
  x0_m_ = y0_m_ = std::numeric_limits<double>::infinity();
  for (const FloorRect& r : footprints) {
    x0_m_ = std::min(x0_m_, r.x0_m - kPad_m);
    y0_m_ = std::min(y0_m_, r.y0_m - kPad_m);
    x1 = std::max(x1, r.x1_m + kPad_m);
    y1 = std::max(y1, r.y1_m + kPad_m);
  }
  square_m_ = square_m;
  while ((x1 - x0_m_) / square_m_ * (y1 - y0_m_) / square_m_ > kMaxSquares) square_m_ *= 2;
  nx_ = std::max(1, static_cast<int>(std::ceil((x1 - x0_m_) / square_m_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((y1 - y0_m_) / square_m_)));

  // counted first, then filled: one array for all squares
  auto range = [&](const FloorRect& r, int& ix0, int& iy0, int& ix1, int& iy1) {
    ix0 =
        std::clamp(static_cast<int>(std::floor((r.x0_m - kPad_m - x0_m_) / square_m_)), 0, nx_ - 1);
    iy0 =
        std::clamp(static_cast<int>(std::floor((r.y0_m - kPad_m - y0_m_) / square_m_)), 0, ny_ - 1);
    ix1 =
        std::clamp(static_cast<int>(std::floor((r.x1_m + kPad_m - x0_m_) / square_m_)), 0, nx_ - 1);
    iy1 =
        std::clamp(static_cast<int>(std::floor((r.y1_m + kPad_m - y0_m_) / square_m_)), 0, ny_ - 1);
  };
  first_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
  for (const FloorRect& r : footprints) {
    int ix0, iy0, ix1, iy1;
    range(r, ix0, iy0, ix1, iy1);
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) ++first_[static_cast<size_t>(iy) * nx_ + ix + 1];
    }
  }
  for (size_t i = 1; i < first_.size(); ++i) first_[i] += first_[i - 1];
  shapes_.resize(static_cast<size_t>(first_.back()));
  std::vector<int> filled(first_.begin(), first_.end() - 1);
  for (int s = 0; s < static_cast<int>(footprints.size()); ++s) {
    int ix0, iy0, ix1, iy1;
    range(footprints[s], ix0, iy0, ix1, iy1);
    for (int iy = iy0; iy <= iy1; ++iy) {
      for (int ix = ix0; ix <= ix1; ++ix) {
        shapes_[static_cast<size_t>(filled[static_cast<size_t>(iy) * nx_ + ix]++)] = s;
      }
    }
  }
  seen_.assign(footprints.size(), 0);
}

void FloorGrid::AddSquare(int ix, int iy, std::vector<int>& out) const {
  if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) return;
  const size_t square = static_cast<size_t>(iy) * nx_ + ix;
  for (int i = first_[square]; i < first_[square + 1]; ++i) {
    const int s = shapes_[static_cast<size_t>(i)];
    if (seen_[static_cast<size_t>(s)] != stamp_) {
      seen_[static_cast<size_t>(s)] = stamp_;
      out.push_back(s);
    }
  }
}

void FloorGrid::ShapesNear(const FloorRect& area, std::vector<int>& out) const {
  // a rectangle off the grid, or not a rectangle (NaN): nothing there
  const double x1_m = x0_m_ + nx_ * square_m_, y1_m = y0_m_ + ny_ * square_m_;
  if (nx_ == 0 || !(area.x0_m <= area.x1_m && area.y0_m <= area.y1_m) || area.x1_m < x0_m_ ||
      area.y1_m < y0_m_ || area.x0_m > x1_m || area.y0_m > y1_m) {
    return;
  }
  NewQuery();
  const size_t begin = out.size();
  // clamped while still a double: a cast of a number beyond int's range is undefined
  auto square = [this](double at_m, double origin_m, int n) {
    return static_cast<int>(std::clamp(std::floor((at_m - origin_m) / square_m_), 0.0, n - 1.0));
  };
  const int ix0 = square(area.x0_m, x0_m_, nx_), ix1 = square(area.x1_m, x0_m_, nx_);
  const int iy0 = square(area.y0_m, y0_m_, ny_), iy1 = square(area.y1_m, y0_m_, ny_);
  for (int iy = iy0; iy <= iy1; ++iy) {
    for (int ix = ix0; ix <= ix1; ++ix) AddSquare(ix, iy, out);
  }
  std::sort(out.begin() + static_cast<long>(begin), out.end());
}

void FloorGrid::ShapesAlong(double x_m, double y_m, double dx, double dy, double length_m,
                            std::vector<int>& out) const {
  if (nx_ == 0 || !std::isfinite(x_m) || !std::isfinite(y_m) || !std::isfinite(dx) ||
      !std::isfinite(dy) || !std::isfinite(length_m)) {
    return;
  }
  const double norm = std::hypot(dx, dy);
  const double ux = norm > 0 ? dx / norm : 0, uy = norm > 0 ? dy / norm : 0;
  // the part of the segment over the grid (slabs): [enter, leave] metres from its start; a
  // segment that never crosses the grid meets no shape
  double enter = 0, leave = std::max(0.0, length_m);
  const double from[2] = {x_m, y_m}, along[2] = {ux, uy};
  const double lo[2] = {x0_m_, y0_m_}, hi[2] = {x0_m_ + nx_ * square_m_, y0_m_ + ny_ * square_m_};
  for (int k = 0; k < 2; ++k) {
    if (along[k] == 0) {
      if (from[k] < lo[k] || from[k] > hi[k]) return;
      continue;
    }
    const double a = (lo[k] - from[k]) / along[k], b = (hi[k] - from[k]) / along[k];
    enter = std::max(enter, std::min(a, b));
    leave = std::min(leave, std::max(a, b));
  }
  if (enter > leave) return;
  NewQuery();

  // the squares the segment crosses, one after another (a digital differential analyser): from
  // the square where it enters the grid, step into the x or the y neighbour, whichever edge
  // comes first
  const double u = (x_m + ux * enter - x0_m_) / square_m_;
  const double v = (y_m + uy * enter - y0_m_) / square_m_;
  int ix = static_cast<int>(std::clamp(std::floor(u), 0.0, nx_ - 1.0));
  int iy = static_cast<int>(std::clamp(std::floor(v), 0.0, ny_ - 1.0));
  const double length = (leave - enter) / square_m_;  // in squares
  const int step_x = ux > 0 ? 1 : -1, step_y = uy > 0 ? 1 : -1;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  // distance along the segment, in squares, to the next x edge and y edge, and between edges
  double next_x = ux != 0 ? ((step_x > 0 ? ix + 1 - u : u - ix) / std::fabs(ux)) : kNever;
  double next_y = uy != 0 ? ((step_y > 0 ? iy + 1 - v : v - iy) / std::fabs(uy)) : kNever;
  const double every_x = ux != 0 ? 1 / std::fabs(ux) : kNever;
  const double every_y = uy != 0 ? 1 / std::fabs(uy) : kNever;
  for (;;) {
    AddSquare(ix, iy, out);
    const double next = std::min(next_x, next_y);
    if (next > length) break;
    // a square's corner on the segment: both neighbours, so that no shape is skipped
    if (std::fabs(next_x - next_y) < 1e-9) {
      AddSquare(ix + step_x, iy, out);
      AddSquare(ix, iy + step_y, out);
    }
    if (next_x < next_y) {
      ix += step_x;
      next_x += every_x;
    } else {
      iy += step_y;
      next_y += every_y;
    }
    // off the grid: the segment does not come back
    if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) break;
  }
}

void FloorGrid::NewQuery() const {
  if (++stamp_ == 0) {
    std::fill(seen_.begin(), seen_.end(), 0);
    stamp_ = 1;
  }
}

}  // namespace unimouse
