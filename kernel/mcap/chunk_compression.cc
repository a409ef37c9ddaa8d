// SPDX-License-Identifier: GPL-3.0-or-later
#include "chunk_compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include "unimouse/errors.h"

namespace unimouse {

std::string CompressChunk(McapCompression compression, std::string_view records) {
  std::string out;
  switch (compression) {
    case McapCompression::kNone:
      return std::string(records);
    case McapCompression::kZstd: {
      out.resize(ZSTD_compressBound(records.size()));
      // level 1: a recording is written while the run goes on, and its size matters less
      size_t n = ZSTD_compress(out.data(), out.size(), records.data(), records.size(), 1);
      UNIMOUSE_DEMAND(!ZSTD_isError(n));
      out.resize(n);
      return out;
    }
    case McapCompression::kLz4: {
      LZ4F_preferences_t preferences = LZ4F_INIT_PREFERENCES;
      // the frame says how long its content is, which readers may use to size their buffer
      preferences.frameInfo.contentSize = records.size();
      out.resize(LZ4F_compressFrameBound(records.size(), &preferences));
      size_t n =
          LZ4F_compressFrame(out.data(), out.size(), records.data(), records.size(), &preferences);
      UNIMOUSE_DEMAND(!LZ4F_isError(n));
      out.resize(n);
      return out;
    }
  }
  UNIMOUSE_DEMAND(false);
  return out;
}

}  // namespace unimouse
