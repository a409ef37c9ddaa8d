// SPDX-License-Identifier: GPL-3.0-or-later
// Reading MCAP files, written from the published specification (mcap.dev/spec, major version 0)
// like the writer, and sharing none of its code: the records of the data section in file order,
// chunks decompressed (zstd, lz4 or none) and their CRC checked. A file cut short (a run that was
// killed) reads up to its last whole record, and says where and why it stopped.
#ifndef UNIMOUSE_MCAP_MCAP_READER_H_
#define UNIMOUSE_MCAP_MCAP_READER_H_

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

namespace unimouse {

/// A channel as its record declares it.
struct McapChannel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
};

/// A schema as its record declares it.
struct McapSchema {
  uint16_t id = 0;
  std::string name;
  std::string encoding;
  std::string data;
};

/// What a reader is handed, record by record, in the order of the file. Channels and schemas
/// come before the first message that names them, in a file that follows the specification.
class McapVisitor {
 public:
  virtual ~McapVisitor() = default;
  virtual void OnSchema(const McapSchema& /*schema*/) {}
  virtual void OnChannel(const McapChannel& /*channel*/) {}
  virtual void OnMessage(uint16_t /*channel_id*/, uint64_t /*log_time_ns*/,
                         std::string_view /*data*/) {}
  virtual void OnAttachment(const std::string& /*name*/, const std::string& /*media_type*/,
                            uint64_t /*log_time_ns*/, std::string_view /*data*/) {}
  virtual void OnMetadata(const std::string& /*name*/,
                          const std::map<std::string, std::string>& /*values*/) {}
};

/// How a file read.
struct McapReadOutcome {
  std::string profile;  ///< the Header's
  std::string library;  ///< the Header's: who wrote the file
  /// "" for a file read to its footer; otherwise why reading stopped early ("the file ends
  /// inside a chunk at byte 123456"): what came before was handed over.
  std::string cut_short;
};

/// Most bytes of one record (a chunk before or after decompression, an attachment): a larger
/// length is taken for a damaged file.
inline constexpr uint64_t kMaxMcapRecord_bytes = uint64_t{1} << 28;

/// Reads the file at `path`, handing every record to `visitor`. Throws InputError
/// "path: reason" for a file that cannot be opened, is empty, is not MCAP, or is of a major
/// version newer than 0; a file damaged or cut short after its Header is read up to the damage.
McapReadOutcome ReadMcap(const std::string& path, McapVisitor& visitor);
/// The same for a file's bytes, named `name` in what it throws.
McapReadOutcome ReadMcapBytes(std::string_view bytes, const std::string& name,
                              McapVisitor& visitor);

}  // namespace unimouse

#endif  // UNIMOUSE_MCAP_MCAP_READER_H_
