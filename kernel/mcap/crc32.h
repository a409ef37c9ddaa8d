// SPDX-License-Identifier: GPL-3.0-or-later
// CRC-32 as zlib and the MCAP specification compute it (reflected polynomial 0xEDB88320), fed in
// pieces.
#ifndef UNIMOUSE_MCAP_CRC32_H_
#define UNIMOUSE_MCAP_CRC32_H_

#include <cstdint>
#include <string_view>

namespace unimouse {

/// Returns the CRC-32 of the bytes before `bytes` (whose CRC-32 is `crc`, 0 for none) and `bytes`.
uint32_t Crc32(uint32_t crc, std::string_view bytes);

}  // namespace unimouse

#endif  // UNIMOUSE_MCAP_CRC32_H_
