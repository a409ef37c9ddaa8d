// SPDX-License-Identifier: GPL-3.0-or-later
#include "mcap_reader.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "chunk_compression.h"
#include "crc32.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

// the specification's record opcodes that a reader of the data section needs
constexpr uint8_t kHeaderOp = 0x01, kFooterOp = 0x02, kSchemaOp = 0x03, kChannelOp = 0x04,
                  kMessageOp = 0x05, kChunkOp = 0x06, kAttachmentOp = 0x09, kMetadataOp = 0x0C,
                  kDataEndOp = 0x0F;

// "\x89MCAP" and then the major version as an ASCII digit, "\r\n"
constexpr std::string_view kMagicStart("\x89MCAP", 5);

// a record's fields, read in order; a field past the record's end makes the record damaged
class Fields {
 public:
  explicit Fields(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T Get() {
    Need(sizeof(T));
    T value = 0;
    for (size_t i = 0; i < sizeof(T); ++i) {
      value |= static_cast<T>(static_cast<T>(static_cast<uint8_t>(bytes_[at_ + i])) << (8 * i));
    }
    at_ += sizeof(T);
    return value;
  }
  std::string_view Bytes(uint64_t n) {
    Need(n);
    std::string_view out = bytes_.substr(at_, n);
    at_ += n;
    return out;
  }
  std::string String() { return std::string(Bytes(Get<uint32_t>())); }
  std::map<std::string, std::string> Strings() {
    Fields pairs(Bytes(Get<uint32_t>()));
    std::map<std::string, std::string> out;
    while (!pairs.done()) {
      std::string key = pairs.String();
      out[key] = pairs.String();
    }
    return out;
  }
  std::string_view Rest() { return Bytes(bytes_.size() - at_); }
  bool done() const { return at_ == bytes_.size(); }

  struct Damaged {};

 private:
  void Need(uint64_t n) const {
    if (n > bytes_.size() - at_) throw Damaged{};
  }
  std::string_view bytes_;
  size_t at_ = 0;
};

// a chunk that cannot be read, and why (a phrase)
struct BadChunk {
  std::string why;
};

class Reader {
 public:
  Reader(const std::string& path, McapVisitor& visitor) : path_(path), visitor_(visitor) {}

  McapReadOutcome Read(std::string_view file) {
    if (file.empty()) throw InputError(path_ + ": the file is empty, not an MCAP recording");
    if (file.size() < 8 || file.compare(0, 5, kMagicStart) != 0 ||
        file.compare(6, 2, "\r\n") != 0) {
      throw InputError(path_ + ": not an MCAP recording (it does not start with MCAP's magic)");
    }
    if (file[5] != '0') {
      throw InputError(path_ + ": an MCAP file of major version " + std::string(1, file[5]) +
                       ", newer than the version 0 this unimouse reads");
    }
    McapReadOutcome outcome;
    std::string_view rest = file.substr(8);
    uint64_t offset = 8;
    bool first = true;
    while (true) {
      if (rest.size() < 9) {
        outcome.cut_short = "the file ends at byte " + std::to_string(offset) +
                            (rest.empty() ? "" : " inside a record") +
                            " before the end of its data";
        break;
      }
      Fields head(rest.substr(0, 9));
      const auto opcode = head.Get<uint8_t>();
      const auto length = head.Get<uint64_t>();
      if (length > rest.size() - 9) {
        outcome.cut_short = "the file ends at byte " + std::to_string(offset + rest.size()) +
                            " inside a record that began at byte " + std::to_string(offset);
        break;
      }
      if (first && opcode != kHeaderOp) {
        throw InputError(path_ + ": not an MCAP recording (no Header after the magic)");
      }
      const std::string_view body = rest.substr(9, length);
      try {
        if (first) {
          Fields header(body);
          outcome.profile = header.String();
          outcome.library = header.String();
        } else if (opcode == kDataEndOp || opcode == kFooterOp) {
          return outcome;  // the summary repeats what the data section said
        } else if (opcode == kChunkOp) {
          Chunk(body);
        } else {
          Record(opcode, body);
        }
      } catch (const Fields::Damaged&) {
        outcome.cut_short = "the record at byte " + std::to_string(offset) + " is damaged";
        break;
      } catch (const BadChunk& e) {
        outcome.cut_short = "the chunk at byte " + std::to_string(offset) + " " + e.why;
        break;
      }
      first = false;
      rest.remove_prefix(9 + length);
      offset += 9 + length;
    }
    return outcome;
  }

 private:
  void Chunk(std::string_view body) {
    Fields chunk(body);
    chunk.Get<uint64_t>();  // message start time
    chunk.Get<uint64_t>();  // message end time
    const auto uncompressed_size = chunk.Get<uint64_t>();
    const auto uncompressed_crc = chunk.Get<uint32_t>();
    const std::string compression = chunk.String();
    const std::string_view records = chunk.Bytes(chunk.Get<uint64_t>());
    if (uncompressed_size > kMaxMcapRecord_bytes) throw Fields::Damaged{};
    std::string plain;
    try {
      plain = DecompressChunk(compression, records, uncompressed_size);
    } catch (const InputError& e) {
      throw BadChunk{e.what()};
    }
    if (uncompressed_crc != 0 && Crc32(0, plain) != uncompressed_crc) {
      throw BadChunk{"fails its CRC check"};
    }
    Fields inner(plain);
    while (!inner.done()) {
      const auto opcode = inner.Get<uint8_t>();
      Record(opcode, inner.Bytes(inner.Get<uint64_t>()));
    }
  }

  void Record(uint8_t opcode, std::string_view body) {
    Fields f(body);
    switch (opcode) {
      case kSchemaOp: {
        McapSchema schema;
        schema.id = f.Get<uint16_t>();
        schema.name = f.String();
        schema.encoding = f.String();
        schema.data = std::string(f.Bytes(f.Get<uint32_t>()));
        visitor_.OnSchema(schema);
        break;
      }
      case kChannelOp: {
        McapChannel channel;
        channel.id = f.Get<uint16_t>();
        channel.schema_id = f.Get<uint16_t>();
        channel.topic = f.String();
        channel.message_encoding = f.String();
        channel.metadata = f.Strings();
        visitor_.OnChannel(channel);
        break;
      }
      case kMessageOp: {
        const auto channel_id = f.Get<uint16_t>();
        f.Get<uint32_t>();  // sequence
        const auto log_time_ns = f.Get<uint64_t>();
        f.Get<uint64_t>();  // publish time
        visitor_.OnMessage(channel_id, log_time_ns, f.Rest());
        break;
      }
      case kAttachmentOp: {
        const auto log_time_ns = f.Get<uint64_t>();
        f.Get<uint64_t>();  // creation time
        const std::string name = f.String();
        const std::string media_type = f.String();
        const std::string_view data = f.Bytes(f.Get<uint64_t>());
        const auto crc = f.Get<uint32_t>();
        if (crc != 0 && Crc32(0, body.substr(0, body.size() - 4)) != crc) throw Fields::Damaged{};
        visitor_.OnAttachment(name, media_type, log_time_ns, data);
        break;
      }
      case kMetadataOp: {
        const std::string name = f.String();
        visitor_.OnMetadata(name, f.Strings());
        break;
      }
      default:
        break;  // indexes and records this reader has no use for
    }
  }

  const std::string& path_;
  McapVisitor& visitor_;
};

}  // namespace

McapReadOutcome ReadMcap(const std::string& path, McapVisitor& visitor) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the recording: " + std::strerror(errno));
  std::ostringstream content;
  content << in.rdbuf();
  return Reader(path, visitor).Read(content.str());
}

McapReadOutcome ReadMcapBytes(std::string_view bytes, const std::string& name,
                              McapVisitor& visitor) {
  return Reader(name, visitor).Read(bytes);
}

}  // namespace unimouse
