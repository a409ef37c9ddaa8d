// SPDX-License-Identifier: GPL-3.0-or-later
// The compression of a chunk's records: a zstd frame (libzstd) or an LZ4 frame (liblz4's frame
// format, which MCAP readers expect, not its raw block format).
#ifndef UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_
#define UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_

#include <string>
#include <string_view>

#include "mcap_writer.h"

namespace unimouse {

/// Returns `records` compressed as `compression` says (a copy for kNone).
std::string CompressChunk(McapCompression compression, std::string_view records);

}  // namespace unimouse

#endif  // UNIMOUSE_MCAP_CHUNK_COMPRESSION_H_
