// SPDX-License-Identifier: GPL-3.0-or-later
#include "mcap_writer.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

#include "chunk_compression.h"
#include "crc32.h"
#include "unimouse/errors.h"

namespace unimouse {
namespace {

// record opcodes (specification, "Records")
enum Opcode : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// "\x89MCAP0\r\n": the byte after MCAP is the major version
constexpr std::string_view kMagic("\x89MCAP0\r\n", 8);

// every integer is little-endian, whatever the machine
template <typename T>
void Put(std::string& out, T value) {
  for (size_t i = 0; i < sizeof(T); ++i)
    out.push_back(static_cast<char>((value >> (8 * i)) & 0xFF));
}

void PutString(std::string& out, std::string_view text) {
  Put<uint32_t>(out, static_cast<uint32_t>(text.size()));
  out.append(text);
}

void PutStrings(std::string& out, const McapStrings& pairs) {
  std::string entries;
  for (const auto& [key, value] : pairs) {
    PutString(entries, key);
    PutString(entries, value);
  }
  PutString(out, entries);
}

std::string Record(uint8_t opcode, std::string_view content) {
  std::string record;
  record.reserve(9 + content.size());
  Put<uint8_t>(record, opcode);
  Put<uint64_t>(record, content.size());
  record.append(content);
  return record;
}

}  // namespace

const char* McapCompressionName(McapCompression compression) {
  switch (compression) {
    case McapCompression::kNone:
      return "";
    case McapCompression::kZstd:
      return "zstd";
    case McapCompression::kLz4:
      return "lz4";
  }
  return "";
}

McapWriter::McapWriter(const std::string& path, McapWriterOptions options)
    : path_(path), options_(std::move(options)) {
  file_ = std::fopen(path.c_str(), "wb");
  if (file_ == nullptr) {
    throw InputError(path + ": cannot create the recording: " + std::strerror(errno));
  }
  std::string header;
  PutString(header, options_.profile);
  PutString(header, options_.library);
  try {
    Emit(kMagic);
    EmitRecord(kHeader, header);
  } catch (const InputError&) {
    std::fclose(file_);
    throw;
  }
}

McapWriter::~McapWriter() {
  try {
    Close();
  } catch (const std::exception&) {
    // a destructor cannot report: whoever needs the error calls Close() first
  }
  if (file_ != nullptr) std::fclose(file_);
}

void McapWriter::Demand(bool writable) {
  if (!failure_.empty()) throw InputError(failure_);
  UNIMOUSE_DEMAND(!writable || !closed_);
}

void McapWriter::Emit(std::string_view bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
    failure_ = path_ + ": cannot write the recording: " + std::strerror(errno);
    throw InputError(failure_);
  }
  offset_ += bytes.size();
  data_crc_ = Crc32(data_crc_, bytes);
}

void McapWriter::EmitRecord(uint8_t opcode, std::string_view content) {
  Emit(Record(opcode, content));
}

uint16_t McapWriter::AddSchema(std::string_view name, std::string_view encoding,
                               std::string_view data) {
  Demand(true);
  UNIMOUSE_DEMAND(schemas_.size() < 0xFFFF);
  auto id = static_cast<uint16_t>(schemas_.size() + 1);
  std::string content;
  Put<uint16_t>(content, id);
  PutString(content, name);
  PutString(content, encoding);
  PutString(content, data);
  schemas_.push_back(Record(kSchema, content));

  // inside the chunk, before any message that needs it: a reader of a cut file meets it first
  chunk_ += schemas_.back();
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id, std::string_view topic,
                                std::string_view message_encoding, const McapStrings& metadata) {
  Demand(true);
  UNIMOUSE_DEMAND(schema_id <= schemas_.size());
  UNIMOUSE_DEMAND(channels_.size() < 0xFFFF);
  auto id = static_cast<uint16_t>(channels_.size());
  std::string content;
  Put<uint16_t>(content, id);
  Put<uint16_t>(content, schema_id);
  PutString(content, topic);
  PutString(content, message_encoding);
  PutStrings(content, metadata);
  channels_.push_back(Record(kChannel, content));
  sequence_.push_back(0);
  chunk_ += channels_.back();
  return id;
}

void McapWriter::Write(uint16_t channel_id, uint64_t log_time_ns, std::string_view data) {
  Demand(true);
  UNIMOUSE_DEMAND(channel_id < channels_.size());
  if (!chunk_messages_.empty() && log_time_ns >= chunk_start_ns_ &&
      log_time_ns - chunk_start_ns_ >= options_.chunk_span_ns) {
    CloseChunk();
  }
  if (chunk_messages_.empty()) {
    chunk_start_ns_ = chunk_end_ns_ = log_time_ns;
  }
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  chunk_messages_[channel_id].emplace_back(log_time_ns, chunk_.size());

  Put<uint8_t>(chunk_, kMessage);
  Put<uint64_t>(chunk_, 2 + 4 + 8 + 8 + data.size());
  Put<uint16_t>(chunk_, channel_id);
  Put<uint32_t>(chunk_, ++sequence_[channel_id]);
  Put<uint64_t>(chunk_, log_time_ns);
  Put<uint64_t>(chunk_, log_time_ns);
  chunk_.append(data);

  if (message_count_ == 0) first_ns_ = last_ns_ = log_time_ns;
  first_ns_ = std::min(first_ns_, log_time_ns);
  last_ns_ = std::max(last_ns_, log_time_ns);
  ++message_count_;
  ++message_counts_[channel_id];
  if (chunk_.size() >= options_.chunk_size_bytes) CloseChunk();
}

void McapWriter::Attach(std::string_view name, std::string_view media_type, uint64_t log_time_ns,
                        std::string_view data) {
  Demand(true);
  std::string content;
  Put<uint64_t>(content, log_time_ns);
  Put<uint64_t>(content, 0);  // no creation time known
  PutString(content, name);
  PutString(content, media_type);
  Put<uint64_t>(content, data.size());
  content.append(data);
  Put<uint32_t>(content, Crc32(0, content));
  AttachmentEntry entry{offset_,     9 + content.size(), log_time_ns,
                        data.size(), std::string(name),  std::string(media_type)};
  EmitRecord(kAttachment, content);
  attachment_indexes_.push_back(std::move(entry));
}

void McapWriter::AddMetadata(std::string_view name, const McapStrings& metadata) {
  Demand(true);
  std::string content;
  PutString(content, name);
  PutStrings(content, metadata);
  NamedOffset entry{offset_, 9 + content.size(), std::string(name)};
  EmitRecord(kMetadata, content);
  metadata_indexes_.push_back(std::move(entry));
}

void McapWriter::CloseChunk() {
  if (chunk_.empty()) return;
  std::string compressed = CompressChunk(options_.compression, chunk_);
  ChunkIndexEntry index{};
  if (!chunk_messages_.empty()) {
    index.start_ns = chunk_start_ns_;
    index.end_ns = chunk_end_ns_;
  }
  index.compressed_size = compressed.size();
  index.uncompressed_size = chunk_.size();

  std::string content;
  Put<uint64_t>(content, index.start_ns);
  Put<uint64_t>(content, index.end_ns);
  Put<uint64_t>(content, chunk_.size());
  Put<uint32_t>(content, Crc32(0, chunk_));
  PutString(content, McapCompressionName(options_.compression));
  Put<uint64_t>(content, compressed.size());
  content.append(compressed);
  index.offset = offset_;
  index.length = 9 + content.size();

  // the chunk and its message indexes go out in one piece, so a cut file ends at a whole chunk
  // or has its indexes to check against
  std::string out = Record(kChunk, content);
  for (const auto& [channel_id, entries] : chunk_messages_) {
    std::string index_content;
    Put<uint16_t>(index_content, channel_id);
    Put<uint32_t>(index_content, static_cast<uint32_t>(entries.size() * 16));
    for (const auto& [time_ns, offset] : entries) {
      Put<uint64_t>(index_content, time_ns);
      Put<uint64_t>(index_content, offset);
    }
    index.index_offsets[channel_id] = offset_ + out.size();
    out += Record(kMessageIndex, index_content);
  }
  index.index_length = offset_ + out.size() - index.offset - index.length;
  chunk_.clear();
  chunk_messages_.clear();
  Emit(out);
  chunk_indexes_.push_back(std::move(index));
  if (std::fflush(file_) != 0) {
    failure_ = path_ + ": cannot write the recording: " + std::strerror(errno);
    throw InputError(failure_);
  }
}

void McapWriter::Flush() {
  Demand(true);
  CloseChunk();
  if (std::fflush(file_) != 0) {
    failure_ = path_ + ": cannot write the recording: " + std::strerror(errno);
    throw InputError(failure_);
  }
}

void McapWriter::Close() {
  if (closed_) return;
  Demand(true);
  CloseChunk();
  std::string data_end;
  Put<uint32_t>(data_end, data_crc_);
  EmitRecord(kDataEnd, data_end);
  WriteSummary();
  closed_ = true;
  int closing = std::fclose(file_);
  file_ = nullptr;
  if (closing != 0) {
    failure_ = path_ + ": cannot write the recording: " + std::strerror(errno);
    throw InputError(failure_);
  }
}

void McapWriter::WriteSummary() {
  const uint64_t summary_start = offset_;
  std::string summary;

  // records grouped by opcode, each group's place kept for its Summary Offset
  std::vector<std::pair<uint8_t, std::pair<uint64_t, uint64_t>>> groups;
  auto group = [&](uint8_t opcode, auto&& write_records) {
    size_t start = summary.size();
    write_records();
    if (summary.size() > start) {
      groups.push_back({opcode, {summary_start + start, summary.size() - start}});
    }
  };
  group(kSchema, [&] {
    for (const auto& record : schemas_) summary += record;
  });
  group(kChannel, [&] {
    for (const auto& record : channels_) summary += record;
  });
  group(kStatistics, [&] {
    std::string content;
    Put<uint64_t>(content, message_count_);
    Put<uint16_t>(content, static_cast<uint16_t>(schemas_.size()));
    Put<uint32_t>(content, static_cast<uint32_t>(channels_.size()));
    Put<uint32_t>(content, static_cast<uint32_t>(attachment_indexes_.size()));
    Put<uint32_t>(content, static_cast<uint32_t>(metadata_indexes_.size()));
    Put<uint32_t>(content, static_cast<uint32_t>(chunk_indexes_.size()));
    Put<uint64_t>(content, first_ns_);
    Put<uint64_t>(content, last_ns_);
    std::string counts;
    for (const auto& [channel_id, count] : message_counts_) {
      Put<uint16_t>(counts, channel_id);
      Put<uint64_t>(counts, count);
    }
    PutString(content, counts);
    summary += Record(kStatistics, content);
  });
  group(kChunkIndex, [&] {
    for (const auto& index : chunk_indexes_) {
      std::string content;
      Put<uint64_t>(content, index.start_ns);
      Put<uint64_t>(content, index.end_ns);
      Put<uint64_t>(content, index.offset);
      Put<uint64_t>(content, index.length);
      std::string offsets;
      for (const auto& [channel_id, offset] : index.index_offsets) {
        Put<uint16_t>(offsets, channel_id);
        Put<uint64_t>(offsets, offset);
      }
      PutString(content, offsets);
      Put<uint64_t>(content, index.index_length);
      PutString(content, McapCompressionName(options_.compression));
      Put<uint64_t>(content, index.compressed_size);
      Put<uint64_t>(content, index.uncompressed_size);
      summary += Record(kChunkIndex, content);
    }
  });
  group(kAttachmentIndex, [&] {
    for (const auto& index : attachment_indexes_) {
      std::string content;
      Put<uint64_t>(content, index.offset);
      Put<uint64_t>(content, index.length);
      Put<uint64_t>(content, index.log_time_ns);
      Put<uint64_t>(content, 0);
      Put<uint64_t>(content, index.data_size);
      PutString(content, index.name);
      PutString(content, index.media_type);
      summary += Record(kAttachmentIndex, content);
    }
  });
  group(kMetadataIndex, [&] {
    for (const auto& index : metadata_indexes_) {
      std::string content;
      Put<uint64_t>(content, index.offset);
      Put<uint64_t>(content, index.length);
      PutString(content, index.name);
      summary += Record(kMetadataIndex, content);
    }
  });

  const uint64_t summary_offset_start = summary_start + summary.size();
  for (const auto& [opcode, place] : groups) {
    std::string content;
    Put<uint8_t>(content, opcode);
    Put<uint64_t>(content, place.first);
    Put<uint64_t>(content, place.second);
    summary += Record(kSummaryOffset, content);
  }

  // the summary's CRC covers it, the summary offsets and the footer up to the CRC itself
  std::string footer;
  Put<uint8_t>(footer, kFooter);
  Put<uint64_t>(footer, 8 + 8 + 4);
  Put<uint64_t>(footer, summary_start);
  Put<uint64_t>(footer, summary_offset_start);
  Put<uint32_t>(footer, Crc32(Crc32(0, summary), footer));
  Emit(summary);
  Emit(footer);
  Emit(kMagic);
}

}  // namespace unimouse
