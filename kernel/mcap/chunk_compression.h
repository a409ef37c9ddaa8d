// SPDX-License-Identifier: GPL-3.0-or-later
// The compression of a chunk's records, both ways: a zstd frame (libzstd) or an LZ4 frame (liblz4's
// frame format, which MCAP readers expect, not its raw block format).
#ifndef UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_
#define UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "mcap_writer.h"

namespace unimouse {

/// Returns `records` compressed as `compression` says (a copy for kNone).
std::string CompressChunk(McapCompression compression, std::string_view records);

/// Returns a chunk's records from their compressed form, `compression` as the chunk names it
/// ("", "zstd" or "lz4"), checking that they come to `size` bytes. Throws InputError with a
/// phrase ("uses compression xz, which this unimouse cannot read") for anything else.
std::string DecompressChunk(const std::string& compression, std::string_view compressed,
                            uint64_t size);

}  // namespace unimouse

#endif  // UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_
