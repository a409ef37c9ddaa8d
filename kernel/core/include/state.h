// SPDX-License-Identifier: GPL-3.0-or-later
// Everything that changes during a run: MuJoCo's mjData, each component's state slice, the
// signals between components, the random streams and the step count. Snapshots, resets and
// determinism checks all work on this.
#ifndef UNIMOUSE_CORE_STATE_H_
#define UNIMOUSE_CORE_STATE_H_

#include <mujoco/mujoco.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "rng.h"

namespace unimouse {

class State {
 public:
  /// Allocates a state for the model; `model` must outlive it.
  State(const mjModel& model, int component_state_size, int signal_count);

  mjData& data() { return *data_; }
  const mjData& data() const { return *data_; }
  std::vector<double>& component_state() { return component_state_; }
  std::vector<double>& signals() { return signals_; }
  const std::vector<double>& signals() const { return signals_; }
  std::vector<RngStream>& rngs() { return rngs_; }
  int64_t step() const { return step_; }
  void set_step(int64_t step) { step_ = step; }

  /// Copies another state of the same model into this one.
  void CopyFrom(const State& other);
  /// Returns a hash of everything that determines the future of the run.
  uint64_t Hash() const;

 private:
  struct DataDeleter {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };

  const mjModel* model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  std::vector<double> component_state_;
  std::vector<double> signals_;
  std::vector<RngStream> rngs_;
  int64_t step_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_STATE_H_
