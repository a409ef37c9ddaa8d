// SPDX-License-Identifier: GPL-3.0-or-later
// Named, seeded random streams. Each stream's seed derives from the run seed and its name
// alone, so adding a sensor never changes another sensor's noise. The generator (xoshiro256**)
// and the normal sampler are written here, not taken from the standard library, whose
// distributions differ between implementations.
#ifndef UNIMOUSE_CORE_RNG_H_
#define UNIMOUSE_CORE_RNG_H_

#include <array>
#include <cstdint>
#include <string_view>

namespace unimouse {

class RngStream {
 public:
  RngStream() = default;
  /// Seeds the stream from the run seed and the stream's name.
  RngStream(uint64_t run_seed, std::string_view name);

  uint64_t NextBits();
  /// Returns a uniform double in [0, 1).
  double Uniform();
  /// Returns a standard normal sample (Marsaglia's polar method).
  double Normal();

  bool operator==(const RngStream&) const = default;
  /// Folds the stream's state into a running FNV-1a hash.
  uint64_t HashInto(uint64_t hash) const;

 private:
  std::array<uint64_t, 4> s_{};
  double spare_ = 0;
  bool has_spare_ = false;
};

/// 64-bit FNV-1a over bytes; used for stream seeds and state hashes.
uint64_t Fnv1a(const void* data, size_t size, uint64_t hash = 0xcbf29ce484222325ULL);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_RNG_H_
