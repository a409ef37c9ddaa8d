// SPDX-License-Identifier: GPL-3.0-or-later
#include "tof_sensor.h"

#include <algorithm>

namespace unimouse::plugins {

TofSensor::TofSensor(Params params) : p_(std::move(params)) {
  UNIMOUSE_THROW_UNLESS(p_.range_min_m < p_.range_max_m,
                        "range_min_m must be less than range_max_m");
}

void TofSensor::Bind(BindContext& ctx) {
  site_ = ctx.SiteId(p_.site);
  range_ = ctx.WriteSignal(p_.range_out);
  if (!p_.true_range_out.empty()) true_range_ = ctx.WriteSignal(p_.true_range_out);
  noise_ = ctx.Rng(ctx.name());
  // the host draws the beam from the declaration alone
  ctx.DeclareBeam(site_, range_, p_.range_max_m);
}

void TofSensor::Reset(const ResetContext& ctx) const {
  ctx.Write(range_, p_.range_max_m);
  if (true_range_.index >= 0) ctx.Write(true_range_, -1);
}

void TofSensor::Sense(const SenseContext& ctx) const {
  const mjData& d = ctx.data();
  const double* origin = d.site_xpos + 3 * site_;
  const double* r = d.site_xmat + 9 * site_;  // row-major: column 0 is the site's x axis
  const double beam[3] = {r[0], r[3], r[6]};
  const double true_m = ctx.CastRay(origin, beam, p_.range_max_m);
  if (true_range_.index >= 0) ctx.Write(true_range_, true_m);

  double reading = p_.range_max_m;
  if (true_m >= p_.range_min_m) {
    reading = std::clamp(true_m + p_.noise_cv * true_m * ctx.Normal(noise_), 0.0, p_.range_max_m);
  }
  ctx.Write(range_, reading);
}

}  // namespace unimouse::plugins
