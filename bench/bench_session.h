// SPDX-License-Identifier: GPL-3.0-or-later
// A whole run through Session, as the command line makes it, for benchmarks of whole challenges.
#ifndef UNIMOUSE_BENCH_BENCH_SESSION_H_
#define UNIMOUSE_BENCH_BENCH_SESSION_H_

#include <benchmark/benchmark.h>

#include "session.h"

namespace unimouse {

/// Runs the challenge `options` describe once per benchmark iteration (bundled components,
/// no pictures, no console, a scratch output directory) and reports its real-time factor and
/// simulated time as counters.
void RunSessionBenchmark(benchmark::State& bench, SessionOptions options);

}  // namespace unimouse

#endif  // UNIMOUSE_BENCH_BENCH_SESSION_H_
