// SPDX-License-Identifier: GPL-3.0-or-later
// VL53L0X time-of-flight range sensor (dissertation section 3.2.4, table 3.8). Every period
// (30 ms) it casts a ray from its site along the site's x axis; the ray sees walls, obstacles
// and the floor but no robot. A hit at true distance z* reads z* + N(0, (c_v z*)^2) (eq. 3.20-
// 3.22), clamped at 0. The sensor reports "no valid target" as range_max_m, which the link
// sends as 0xFFFF: when nothing is hit within range, when the reading reaches range_max_m, and
// when the target is nearer than range_min_m (the VL53L0X's blind zone, about 3 cm).
#ifndef UNIMOUSE_PLUGINS_TOF_SENSOR_H_
#define UNIMOUSE_PLUGINS_TOF_SENSOR_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct TofSensorParams {
  std::string site;
  double range_min_m = 0.03;
  double range_max_m = 1.2;
  double noise_cv = 0.028084;
  std::string range_out;
  std::string true_range_out;

  template <class V>
  void Visit(V& v) {
    v("site", site, "MuJoCo site the sensor sits at; its x axis is the beam", param::Required{});
    v("range_min_m", range_min_m, "nearest valid target (table 3.8)", param::NonNegative{});
    v("range_max_m", range_max_m, "farthest valid target and full scale (table 3.8)",
      param::Positive{});
    v("noise_cv", noise_cv, "coefficient of variation of the readings (table 3.8)",
      param::NonNegative{});
    v("range_out", range_out, "signal it writes: the reading, metres; range_max_m = no target",
      param::Required{});
    v("true_range_out", true_range_out,
      "signal it writes: the true distance, metres (-1 when no hit); for logs and tests");
  }
};

class TofSensor final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.tof_sensor";
  static constexpr const char* kSummary = "VL53L0X time-of-flight range sensor (table 3.8)";
  static constexpr double kDefaultPeriod_s = 0.03;
  using Params = TofSensorParams;

  explicit TofSensor(Params params);
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;

 private:
  const Params p_;
  int site_ = -1;
  SignalId range_, true_range_;
  RngId noise_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_TOF_SENSOR_H_
