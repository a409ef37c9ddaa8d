// SPDX-License-Identifier: GPL-3.0-or-later
// Writes an MCAP file with the official TypeScript writer (npm @mcap/core), for the tests of
// unimouse's reader to read something it did not write itself:
//
//   node mcap_core_write.cjs NODE_MODULES zstd|lz4|none FILE
//
// What it writes, which the test knows: schema "test.Count" (jsonschema), channels "/even" and
// "/odd" on it; messages i = 0..999 at log time i ms on "/even" or "/odd" by i's parity, data
// {"i": i}; after message 500 an attachment "notes.txt" (text/plain, "hello") at 0.5 s and
// metadata "test.meta" {a: "1", b: "two"}. Chunks of at most 4 KiB, compressed as asked.
"use strict";

const fs = require("fs");
const path = require("path");
const { createRequire } = require("module");

async function main() {
  const [modules, compression, file] = process.argv.slice(2);
  const load = createRequire(path.join(path.resolve(modules), "unimouse.cjs"));
  const { McapWriter } = load("@mcap/core");
  const zstd = load("@foxglove/wasm-zstd");
  await zstd.isLoaded;
  const compressors = {
    zstd: (data) => ({ compression: "zstd", compressedData: zstd.compress(data) }),
    none: (data) => ({ compression: "", compressedData: data }),
  };
  if (!(compression in compressors)) throw new Error("no compressor " + compression);
  const out = fs.openSync(file, "w");
  let position = 0n;
  const writable = {
    position: () => position,
    write: async (buffer) => {
      fs.writeSync(out, buffer);
      position += BigInt(buffer.length);
    },
  };
  const writer = new McapWriter({
    writable,
    useChunks: true,
    chunkSize: 4096,
    compressChunk: compressors[compression],
  });
  const bytes = (text) => new TextEncoder().encode(text);
  await writer.start({ profile: "", library: "mcap_core_write" });
  const schemaId = await writer.registerSchema({
    name: "test.Count",
    encoding: "jsonschema",
    data: bytes('{"type":"object","properties":{"i":{"type":"integer"}}}'),
  });
  const even = await writer.registerChannel({
    topic: "/even", schemaId, messageEncoding: "json", metadata: new Map([["side", "even"]]),
  });
  const odd = await writer.registerChannel({
    topic: "/odd", schemaId, messageEncoding: "json", metadata: new Map(),
  });
  for (let i = 0; i < 1000; ++i) {
    const t = BigInt(i) * 1000000n;
    await writer.addMessage({
      channelId: i % 2 === 0 ? even : odd,
      sequence: i,
      logTime: t,
      publishTime: t,
      data: bytes(JSON.stringify({ i })),
    });
    if (i === 500) {
      await writer.addAttachment({
        name: "notes.txt", logTime: 500000000n, createTime: 0n, mediaType: "text/plain",
        data: bytes("hello"),
      });
      await writer.addMetadata({ name: "test.meta", metadata: new Map([["a", "1"], ["b", "two"]]) });
    }
  }
  await writer.end();
  fs.closeSync(out);
}

main().catch((error) => {
  process.stderr.write(String(error && error.stack ? error.stack : error) + "\n");
  process.exit(1);
});
