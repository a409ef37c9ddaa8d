// SPDX-License-Identifier: GPL-3.0-or-later
#include "chunk_compression.h"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>

#include "unimouse/errors.h"

namespace unimouse {

std::string CompressChunk(McapCompression compression, std::string_view records) {
  // compressed into a buffer of the worst case's size, left uninitialised: zeroing a
  // megabyte for every chunk showed in a run's time
  size_t bound = 0, n = 0;
  std::unique_ptr<char[]> out;
  switch (compression) {
    case McapCompression::kNone:
      return std::string(records);
    case McapCompression::kZstd:
      bound = ZSTD_compressBound(records.size());
      out.reset(new char[bound]);
      // level 1: a recording is written while the run goes on, and its size matters less
      n = ZSTD_compress(out.get(), bound, records.data(), records.size(), 1);
      UNIMOUSE_DEMAND(!ZSTD_isError(n));
      return std::string(out.get(), n);
    case McapCompression::kLz4: {
      LZ4F_preferences_t preferences = LZ4F_INIT_PREFERENCES;
      // the frame says how long its content is, which readers may use to size their buffer
      preferences.frameInfo.contentSize = records.size();
      bound = LZ4F_compressFrameBound(records.size(), &preferences);
      out.reset(new char[bound]);
      n = LZ4F_compressFrame(out.get(), bound, records.data(), records.size(), &preferences);
      UNIMOUSE_DEMAND(!LZ4F_isError(n));
      return std::string(out.get(), n);
    }
  }
  UNIMOUSE_DEMAND(false);
  return "";
}

std::string DecompressChunk(const std::string& compression, std::string_view compressed,
                            uint64_t size) {
  std::string out(size, '\0');
  if (size == 0 && compressed.empty()) return out;
  if (compression.empty()) {
    if (compressed.size() != size) throw InputError("is not as long as it says");
    return std::string(compressed);
  }
  if (compression == "zstd") {
    const size_t n = ZSTD_decompress(out.data(), out.size(), compressed.data(), compressed.size());
    if (ZSTD_isError(n) || n != size) throw InputError("cannot be decompressed (zstd)");
    return out;
  }
  if (compression == "lz4") {
    LZ4F_dctx* context = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&context, LZ4F_VERSION))) {
      throw InputError("cannot be decompressed (lz4)");
    }
    size_t written = 0, read = 0;
    size_t status = 1;
    // one frame, possibly in several calls: it is complete when the decoder says 0 remains
    while (status != 0 && read < compressed.size() && written < out.size()) {
      size_t out_n = out.size() - written, in_n = compressed.size() - read;
      status = LZ4F_decompress(context, out.data() + written, &out_n, compressed.data() + read,
                               &in_n, nullptr);
      if (LZ4F_isError(status)) break;
      written += out_n;
      read += in_n;
      if (out_n == 0 && in_n == 0) break;
    }
    LZ4F_freeDecompressionContext(context);
    if (LZ4F_isError(status) || status != 0 || written != size) {
      throw InputError("cannot be decompressed (lz4)");
    }
    return out;
  }
  throw InputError("uses compression " + compression + ", which this unimouse cannot read");
}

}  // namespace unimouse
