// SPDX-License-Identifier: GPL-3.0-or-later
// Incremental encoder on the motor shaft (dissertation section 3.2.3, table 4.5). Each period it
// turns the motor shaft's change of angle into whole counts by algorithm 1, carrying the
// fractional remainder, and writes the signed count delta. The shaft turns gear_ratio times per
// wheel turn: 12 counts x 29.86 = 358.32 counts per wheel revolution by default.
//
// The change of angle is the wheel hinge's position change times the gear ratio; with a one-step
// period it equals eq. 3.19's w dt for MuJoCo's integrators, and it stays exact for longer
// periods. Options: x4 quadrature decoding (every edge of both channels, table 3.5), and jitter of
// the edge positions (Gaussian, in counts), which never accumulates into drift.
#ifndef UNIMOUSE_PLUGINS_ENCODER_H_
#define UNIMOUSE_PLUGINS_ENCODER_H_

#include <string>

#include "unimouse/component.h"

namespace unimouse::plugins {

struct EncoderParams {
  std::string joint;
  double gear_ratio = 29.86;
  int cpr = 12;
  bool quadrature_x4 = false;
  double jitter_counts_sd = 0;
  std::string counts_out;

  template <class V>
  void Visit(V& v) {
    v("joint", joint, "wheel hinge whose motor shaft it reads", param::Required{});
    v("gear_ratio", gear_ratio, "motor shaft turns per wheel turn", param::Positive{});
    v("cpr", cpr, "counts per motor shaft revolution (table 4.5)", param::Range{1, 100000});
    v("quadrature_x4", quadrature_x4, "count every edge of both channels: 4 x cpr");
    v("jitter_counts_sd", jitter_counts_sd, "standard deviation of edge positions, in counts",
      param::NonNegative{});
    v("counts_out", counts_out, "signal it writes: counts since its previous period",
      param::Required{});
  }
};

class Encoder final : public Component {
 public:
  static constexpr const char* kTypeName = "unimouse.encoder";
  static constexpr const char* kSummary = "incremental encoder on the motor shaft (algorithm 1)";
  static constexpr double kDefaultPeriod_s = 0;
  using Params = EncoderParams;

  explicit Encoder(Params params);
  void Bind(BindContext& ctx) override;
  void Reset(const ResetContext& ctx) const override;
  void Sense(const SenseContext& ctx) const override;

 private:
  const Params p_;
  const double count_angle_rad_;  // theta_p, eq. 3.17
  int qpos_ = -1;
  SignalId counts_;
  RngId jitter_;
};

}  // namespace unimouse::plugins

#endif  // UNIMOUSE_PLUGINS_ENCODER_H_
