// SPDX-License-Identifier: GPL-3.0-or-later
// MCAP files, written from the published specification (mcap.dev/spec, major version 0): the
// open container of timestamped messages that Foxglove, Lichtblick, PlotJuggler and Rerun read.
// Messages go into chunks, compressed with zstd or lz4, each followed by its message indexes;
// closing the file adds the summary (schemas, channels, statistics and the indexes of chunks,
// attachments and metadata) and the footer. Chunks are closed at a size and at a span of log
// time, and written out at once, so that a file cut short reads up to its last whole chunk.
#ifndef UNIMOUSE_MCAP_MCAP_WRITER_H_
#define UNIMOUSE_MCAP_MCAP_WRITER_H_

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace unimouse {

/// How the records inside a chunk are compressed.
enum class McapCompression { kNone, kZstd, kLz4 };

/// Returns the name a chunk gives its compression: "", "zstd" or "lz4".
const char* McapCompressionName(McapCompression compression);

/// Key-value pairs of a channel or a metadata record, in key order (so the bytes written are
/// the same from run to run).
using McapStrings = std::map<std::string, std::string>;

/// How an McapWriter lays out its file.
struct McapWriterOptions {
  /// The compression of every chunk.
  McapCompression compression = McapCompression::kZstd;
  /// A chunk is closed once its records reach this many bytes before compression.
  size_t chunk_size_bytes = 1024 * 1024;
  /// A chunk is closed before a message whose log time is this far past the chunk's first
  /// message: a file cut short loses at most about this much of the end.
  uint64_t chunk_span_ns = 1'000'000'000;
  /// The Header's profile: "" for none of the specification's well-known profiles.
  std::string profile;
  /// The Header's library: who wrote the file.
  std::string library = "unimouse";
};

/// Writes one MCAP file. Not copyable; single-threaded. Every method that writes throws
/// InputError "path: reason" when the file cannot be written, and again on every later call.
class McapWriter {
 public:
  /// Creates (or truncates) the file at `path` and writes its magic and Header.
  McapWriter(const std::string& path, McapWriterOptions options);
  /// Closes the file as Close() does; an error then is dropped (call Close() to see it).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Adds a schema and returns its id (from 1). `encoding` is "jsonschema" for a JSON Schema,
  /// "" for none.
  uint16_t AddSchema(std::string_view name, std::string_view encoding, std::string_view data);
  /// Adds a channel on `topic` whose messages follow schema `schema_id` (0: no schema) and
  /// returns its id (from 0).
  uint16_t AddChannel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding,
                      const McapStrings& metadata = {});
  /// Writes a message on a channel at `log_time_ns` (also its publish time), numbered in its
  /// channel from 1.
  void Write(uint16_t channel_id, uint64_t log_time_ns, std::string_view data);
  /// Writes a file into the recording (between chunks, as the specification requires).
  void Attach(std::string_view name, std::string_view media_type, uint64_t log_time_ns,
              std::string_view data);
  /// Writes a named set of key-value pairs.
  void AddMetadata(std::string_view name, const McapStrings& metadata);
  /// Closes the open chunk, if any, and hands everything written to the operating system.
  void Flush();
  /// Ends the data section and writes the summary, the footer and the closing magic; later
  /// calls do nothing.
  void Close();

  /// Returns the path of the file.
  const std::string& path() const { return path_; }

 private:
  struct ChunkIndexEntry {
    uint64_t start_ns, end_ns, offset, length, index_length, compressed_size, uncompressed_size;
    std::map<uint16_t, uint64_t> index_offsets;
  };
  struct NamedOffset {
    uint64_t offset, length;
    std::string name;
  };
  struct AttachmentEntry {
    uint64_t offset, length, log_time_ns, data_size;
    std::string name, media_type;
  };

  void Demand(bool writable);
  void Emit(std::string_view bytes);
  void EmitRecord(uint8_t opcode, std::string_view content);
  void CloseChunk();
  void WriteSummary();

  std::string path_;
  McapWriterOptions options_;
  std::FILE* file_ = nullptr;
  std::string failure_;
  bool closed_ = false;
  uint64_t offset_ = 0;
  uint32_t data_crc_ = 0;

  // the schema and channel records as written, kept for the summary
  std::vector<std::string> schemas_;
  std::vector<std::string> channels_;
  std::vector<uint32_t> sequence_;

  // the open chunk: its records, and for each channel (log time, offset) of its messages
  std::string chunk_;
  uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_messages_;

  std::vector<ChunkIndexEntry> chunk_indexes_;
  std::vector<AttachmentEntry> attachment_indexes_;
  std::vector<NamedOffset> metadata_indexes_;
  std::map<uint16_t, uint64_t> message_counts_;
  uint64_t message_count_ = 0;
  uint64_t first_ns_ = 0, last_ns_ = 0;
};

}  // namespace unimouse

#endif  // UNIMOUSE_MCAP_MCAP_WRITER_H_
