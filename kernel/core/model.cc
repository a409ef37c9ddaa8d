// SPDX-License-Identifier: GPL-3.0-or-later
#include "model.h"

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

}  // namespace unimouse
