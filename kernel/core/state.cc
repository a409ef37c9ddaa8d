// SPDX-License-Identifier: GPL-3.0-or-later
#include "state.h"

#include "mujoco_guard.h"
#include "unimouse/errors.h"

namespace unimouse {

State::State(const mjModel& model, int component_state_size, int signal_count)
    : model_(&model),
      data_([&model] {
        mjData* d = nullptr;
        GuardMujoco([&] { d = mj_makeData(&model); });
        return d;
      }()),
      component_state_(static_cast<size_t>(component_state_size), 0.0),
      signals_(static_cast<size_t>(signal_count), 0.0) {
  UNIMOUSE_DEMAND(data_ != nullptr);
}

void State::CopyFrom(const State& other) {
  UNIMOUSE_DEMAND(model_ == other.model_);
  GuardMujoco([&] { mj_copyData(data_.get(), model_, other.data_.get()); });
  component_state_ = other.component_state_;
  signals_ = other.signals_;
  rngs_ = other.rngs_;
  step_ = other.step_;
}

uint64_t State::Hash() const {
  const mjModel& m = *model_;
  const mjData& d = *data_;
  uint64_t h = Fnv1a(&d.time, sizeof(d.time));
  h = Fnv1a(d.qpos, sizeof(mjtNum) * m.nq, h);
  h = Fnv1a(d.qvel, sizeof(mjtNum) * m.nv, h);
  h = Fnv1a(d.act, sizeof(mjtNum) * m.na, h);
  h = Fnv1a(d.ctrl, sizeof(mjtNum) * m.nu, h);
  h = Fnv1a(d.qacc_warmstart, sizeof(mjtNum) * m.nv, h);
  h = Fnv1a(component_state_.data(), sizeof(double) * component_state_.size(), h);
  h = Fnv1a(signals_.data(), sizeof(double) * signals_.size(), h);
  for (const auto& rng : rngs_) h = rng.HashInto(h);
  return Fnv1a(&step_, sizeof(step_), h);
}

}  // namespace unimouse
