// SPDX-License-Identifier: GPL-3.0-or-later
#include "model.h"

#include <algorithm>
#include <cmath>

namespace unimouse {

Model::~Model() {
  for (auto& c : components) {
    if (c.self != nullptr) c.type->destroy(c.self);
  }
}

int Model::FindSignal(const std::string& name) const {
  for (size_t i = 0; i < signal_names.size(); ++i) {
    if (signal_names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

BeamLine BeamLineOf(const BeamSpec& beam, const mjData& d, const std::vector<double>& signals) {
  const mjtNum* from = d.site_xpos + 3 * beam.site;
  const mjtNum* r = d.site_xmat + 9 * beam.site;  // column 0: the beam's direction
  const double reading = signals[static_cast<size_t>(beam.length_signal)];
  BeamLine line;
  line.hit = reading < beam.range_max_m;
  // a reading that is not a number is no target
  const double length =
      std::isnan(reading) ? beam.range_max_m : std::clamp(reading, 0.0, beam.range_max_m);
  for (int i = 0; i < 3; ++i) {
    line.from_m[i] = from[i];
    line.to_m[i] = from[i] + length * r[3 * i];
  }
  return line;
}

}  // namespace unimouse
