// SPDX-License-Identifier: GPL-3.0-or-later
#include "rng.h"

#include <cmath>

namespace unimouse {
namespace {

uint64_t SplitMix64(uint64_t& x) {
  uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

uint64_t RotateLeft(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

uint64_t Fnv1a(const void* data, size_t size, uint64_t hash) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

RngStream::RngStream(uint64_t run_seed, std::string_view name) {
  uint64_t x = run_seed ^ Fnv1a(name.data(), name.size());
  for (auto& word : s_) word = SplitMix64(x);
}

uint64_t RngStream::NextBits() {
  const uint64_t result = RotateLeft(s_[1] * 5, 7) * 9;
  const uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = RotateLeft(s_[3], 45);
  return result;
}

uint64_t RngStream::HashInto(uint64_t hash) const {
  hash = Fnv1a(s_.data(), sizeof(s_), hash);
  const double spare = has_spare_ ? spare_ : 0.0;
  hash = Fnv1a(&spare, sizeof(spare), hash);
  const unsigned char flag = has_spare_ ? 1 : 0;
  return Fnv1a(&flag, 1, hash);
}

double RngStream::Uniform() { return static_cast<double>(NextBits() >> 11) * 0x1.0p-53; }

double RngStream::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u, v, s;
  do {
    u = 2 * Uniform() - 1;
    v = 2 * Uniform() - 1;
    s = u * u + v * v;
  } while (s >= 1 || s == 0);
  const double scale = std::sqrt(-2 * std::log(s) / s);
  spare_ = v * scale;
  has_spare_ = true;
  return u * scale;
}

}  // namespace unimouse
