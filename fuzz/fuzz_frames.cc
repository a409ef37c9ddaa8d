// SPDX-License-Identifier: GPL-3.0-or-later
// Any bytes from a firmware, in pieces of any size: the decoder keeps at most one frame pending,
// and cutting the stream differently gives the same frames.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "frame_codec.h"
#include "frame_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const std::vector<unimouse::link::DataFrame> table = [] {
    std::vector<unimouse::link::DataFrame> frames;
    for (const auto& e : unimouse::link::ParseReceiveTable(unimouse::link::kOriginalReceive)) {
      frames.push_back({e.id, e.encoding});
    }
    // and one of each other encoding, as a receive table may declare
    frames.push_back({20, unimouse::link::Encoding::kI16});
    frames.push_back({21, unimouse::link::Encoding::kF32});
    return frames;
  }();
  // the first byte sets the size of the pieces the rest arrives in
  const size_t piece = 1 + data[0] % 64;
  const std::vector<uint8_t> bytes(data + 1, data + size);
  unimouse::link::FrameDecoder whole(table), pieces(table);
  std::vector<unimouse::link::FirmwareFrame> a, b;
  whole.Feed(bytes, a);
  for (size_t at = 0; at < bytes.size(); at += piece) {
    const size_t n = std::min(piece, bytes.size() - at);
    pieces.Feed(std::vector<uint8_t>(bytes.begin() + static_cast<long>(at),
                                     bytes.begin() + static_cast<long>(at + n)),
                b);
  }
  if (a.size() != b.size() || whole.frames() != pieces.frames()) std::abort();
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].id != b[i].id || a[i].text != b[i].text || a[i].data != b[i].data) std::abort();
  }
  return 0;
}
