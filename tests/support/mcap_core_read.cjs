// SPDX-License-Identifier: GPL-3.0-or-later
// Reads an MCAP file with the official TypeScript reader (npm @mcap/core) and prints what it
// found as JSON, for the tests to compare with what they wrote:
//
//   node mcap_core_read.cjs NODE_MODULES indexed|stream FILE
//
// "indexed" reads through the summary and the indexes (McapIndexedReader, CRCs checked);
// "stream" reads record by record (McapStreamReader, as a player of a file still being written
// does) and says whether the file was complete. Exit 1 with the reader's error on stderr.
"use strict";

const fs = require("fs");
const path = require("path");
const { createRequire } = require("module");

async function main() {
  const [modules, mode, file] = process.argv.slice(2);
  // the packages live in the build tree, not beside this script
  const load = createRequire(path.join(path.resolve(modules), "unimouse.cjs"));
  const { McapIndexedReader, McapStreamReader } = load("@mcap/core");
  const zstd = load("@foxglove/wasm-zstd");
  const lz4 = load("@foxglove/wasm-lz4");
  await zstd.isLoaded;
  await lz4.isLoaded;
  const decompressHandlers = {
    zstd: (data, size) => zstd.decompress(data, Number(size)),
    lz4: (data, size) => lz4(data, Number(size)),
  };
  const text = (bytes) => new TextDecoder("utf-8", { fatal: true }).decode(bytes);
  const out = { channels: [], schemas: [], messages: [], attachments: [], metadata: [] };
  const message = (m) => ({
    channel_id: m.channelId,
    sequence: m.sequence,
    log_time: m.logTime.toString(),
    publish_time: m.publishTime.toString(),
    data: text(m.data),
  });
  const channel = (c) => ({
    id: c.id,
    schema_id: c.schemaId,
    topic: c.topic,
    message_encoding: c.messageEncoding,
    metadata: Object.fromEntries(c.metadata),
  });
  const schema = (s) => ({ id: s.id, name: s.name, encoding: s.encoding, data: text(s.data) });
  const attachment = (a) => ({
    name: a.name,
    media_type: a.mediaType,
    log_time: a.logTime.toString(),
    data: text(a.data),
  });
  const metadata = (m) => ({ name: m.name, metadata: Object.fromEntries(m.metadata) });

  const bytes = fs.readFileSync(file);
  if (mode === "indexed") {
    const readable = {
      size: async () => BigInt(bytes.length),
      read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
    };
    const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
    out.channels = [...reader.channelsById.values()].map(channel);
    out.schemas = [...reader.schemasById.values()].map(schema);
    for await (const m of reader.readMessages({ validateCrcs: true })) {
      out.messages.push(message(m));
    }
    for await (const a of reader.readAttachments({ validateCrcs: true })) {
      out.attachments.push(attachment(a));
    }
    for await (const m of reader.readMetadata()) out.metadata.push(metadata(m));
    out.chunk_count = reader.chunkIndexes.length;
    out.statistics = {
      message_count: reader.statistics.messageCount.toString(),
      chunk_count: reader.statistics.chunkCount,
    };
    out.complete = true;
  } else if (mode === "stream") {
    const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
    const channels = new Map();
    const schemas = new Map();
    // fed in pieces, as a file still being written would be
    for (let at = 0; at < bytes.length; at += 65536) {
      reader.append(bytes.subarray(at, at + 65536));
      for (let record; (record = reader.nextRecord()); ) {
        if (record.type === "Message") out.messages.push(message(record));
        // the summary repeats the data section's channels and schemas
        else if (record.type === "Channel") channels.set(record.id, channel(record));
        else if (record.type === "Schema") schemas.set(record.id, schema(record));
        else if (record.type === "Attachment") out.attachments.push(attachment(record));
        else if (record.type === "Metadata") out.metadata.push(metadata(record));
      }
    }
    out.channels = [...channels.values()];
    out.schemas = [...schemas.values()];
    out.complete = reader.done();
  } else {
    throw new Error(`unknown mode ${mode}`);
  }
  process.stdout.write(JSON.stringify(out));
}

main().catch((error) => {
  process.stderr.write(`${error.stack || error}\n`);
  process.exit(1);
});
