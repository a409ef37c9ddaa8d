// SPDX-License-Identifier: GPL-3.0-or-later
// SHA-256 (FIPS 180-4), for the hashes result.json gives of the files a run used: a grader can
// tell which robot, scenario, maze and firmware ran by comparing them with `sha256sum`.
#ifndef UNIMOUSE_CORE_SHA256_H_
#define UNIMOUSE_CORE_SHA256_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace unimouse {

/// A SHA-256 computation fed in pieces.
class Sha256 {
 public:
  Sha256();
  /// Adds bytes to the message.
  void Add(std::string_view bytes);
  /// Returns the digest of everything added, as 64 lowercase hex digits; ends the computation.
  std::string HexDigest();

 private:
  void Compress(const uint8_t* block);

  std::array<uint32_t, 8> state_;
  std::array<uint8_t, 64> block_ = {};
  size_t block_used_ = 0;
  uint64_t length_bytes_ = 0;
};

/// Returns the SHA-256 of `bytes` as 64 lowercase hex digits.
std::string Sha256Hex(std::string_view bytes);

/// Returns the SHA-256 of a file's content as 64 lowercase hex digits, reading it in pieces
/// (a firmware image may be larger than any input file unimouse parses). Throws InputError
/// "path: reason" when it cannot be read.
std::string FileSha256(const std::string& path);

}  // namespace unimouse

#endif  // UNIMOUSE_CORE_SHA256_H_
