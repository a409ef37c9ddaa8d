#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""An MCAP reader for the tests, written from the published specification (mcap.dev/spec), that
shares nothing with unimouse's writer: it reads a file record by record, checks every record,
CRC, index and the summary against what it read itself, and every JSON message against its
channel's JSON Schema, and prints what the file holds as JSON.

    mcap_reader.py FILE [--cut-ok]

Exit 0 and JSON on stdout when the file is valid; exit 1 and one line on stderr naming the first
fault otherwise. With --cut-ok a file that stops short of its end (a run that died) is read up
to its last whole record and reported with "complete": false; anything else wrong in it is
still a fault. Needs python3-zstandard and python3-lz4 (Debian) for compressed chunks and
python3-jsonschema and python3-fastjsonschema for the schemas.
"""

import json
import struct
import sys
import zlib

MAGIC = b"\x89MCAP0\r\n"
OPCODES = {
    0x01: "Header", 0x02: "Footer", 0x03: "Schema", 0x04: "Channel", 0x05: "Message",
    0x06: "Chunk", 0x07: "MessageIndex", 0x08: "ChunkIndex", 0x09: "Attachment",
    0x0A: "AttachmentIndex", 0x0B: "Statistics", 0x0C: "Metadata", 0x0D: "MetadataIndex",
    0x0E: "SummaryOffset", 0x0F: "DataEnd",
}
DATA_OPCODES = {0x03, 0x04, 0x05, 0x06, 0x07, 0x09, 0x0C, 0x0F}
SUMMARY_OPCODES = {0x03, 0x04, 0x08, 0x0A, 0x0B, 0x0D}


class Fault(Exception):
    pass


def demand(cond, message):
    if not cond:
        raise Fault(message)


class Fields:
    """Reads the fields of one record's content, never past its end."""

    def __init__(self, data, what):
        self.data, self.at, self.what = data, 0, what

    def take(self, n):
        demand(self.at + n <= len(self.data), f"{self.what}: a field runs past the record's end")
        piece = self.data[self.at:self.at + n]
        self.at += n
        return piece

    def u8(self):
        return self.take(1)[0]

    def u16(self):
        return struct.unpack("<H", self.take(2))[0]

    def u32(self):
        return struct.unpack("<I", self.take(4))[0]

    def u64(self):
        return struct.unpack("<Q", self.take(8))[0]

    def string(self):
        raw = self.take(self.u32())
        try:
            return raw.decode("utf-8")
        except UnicodeDecodeError:
            raise Fault(f"{self.what}: a string that is not UTF-8")

    def bytes32(self):
        return self.take(self.u32())

    def bytes64(self):
        return self.take(self.u64())

    def rest(self):
        return self.take(len(self.data) - self.at)

    def string_map(self):
        inner = Fields(self.bytes32(), self.what + " map")
        out = {}
        while inner.at < len(inner.data):
            key = inner.string()
            demand(key not in out, f"{self.what}: key {key!r} twice")
            out[key] = inner.string()
        return out

    def u16_u64_map(self):
        inner = Fields(self.bytes32(), self.what + " map")
        out = {}
        while inner.at < len(inner.data):
            key = inner.u16()
            demand(key not in out, f"{self.what}: key {key} twice")
            out[key] = inner.u64()
        return out

    def end(self):
        # records may grow new fields at their end, which a reader skips; this writer adds none
        demand(self.at == len(self.data), f"{self.what}: {len(self.data) - self.at} bytes left over")


def records(data, start, end, what, cut_ok=False):
    """Yields (offset, opcode, content, record length) from data[start:end]; with cut_ok, stops
    quietly at a record that does not fit."""
    at = start
    while at < end:
        if at + 9 > end:
            demand(cut_ok, f"{what}: a record header cut at byte {at}")
            return
        opcode = data[at]
        length = struct.unpack_from("<Q", data, at + 1)[0]
        if at + 9 + length > end:
            demand(cut_ok, f"{what}: record 0x{opcode:02x} at byte {at} runs past the end")
            return
        demand(opcode != 0x00, f"{what}: opcode 0x00 at byte {at}")
        yield at, opcode, bytes(data[at + 9:at + 9 + length]), 9 + length
        at += 9 + length


def decompress(compression, data, size, what):
    if compression == "":
        return data
    if compression == "zstd":
        import zstandard
        return zstandard.ZstdDecompressor().decompress(data, max_output_size=size)
    if compression == "lz4":
        import lz4.frame
        return lz4.frame.decompress(data)
    raise Fault(f"{what}: unknown compression {compression!r}")


class Reader:
    def __init__(self, data, cut_ok):
        self.data, self.cut_ok = data, cut_ok
        self.schemas, self.channels = {}, {}
        self.messages, self.chunks, self.attachments, self.metadata = [], [], [], []
        self.validators = {}  # schema id -> its JSON Schema validator
        self.complete = False

    def schema(self, content, what):
        f = Fields(content, what)
        record = {"id": f.u16(), "name": f.string(), "encoding": f.string(),
                  "data": f.bytes32().decode("utf-8")}
        f.end()
        demand(record["id"] != 0, f"{what}: schema id 0")
        return record

    def channel(self, content, what):
        f = Fields(content, what)
        record = {"id": f.u16(), "schema_id": f.u16(), "topic": f.string(),
                  "message_encoding": f.string(), "metadata": f.string_map()}
        f.end()
        return record

    def validate(self, channel, message, what):
        """Checks a JSON message against its channel's JSON Schema: the schema itself with
        python3-jsonschema, once, and each message with python3-fastjsonschema, which compiles
        the schema to code (a recording's tens of thousands of messages in seconds, not
        minutes)."""
        schema = self.schemas.get(channel["schema_id"])
        if schema is None or schema["encoding"] != "jsonschema":
            return
        import fastjsonschema
        validator = self.validators.get(schema["id"])
        if validator is None:
            import jsonschema
            try:
                parsed = json.loads(schema["data"])
                jsonschema.validators.validator_for(parsed).check_schema(parsed)
                validator = fastjsonschema.compile(parsed)
            except (json.JSONDecodeError, jsonschema.SchemaError,
                    fastjsonschema.JsonSchemaDefinitionException) as e:
                raise Fault(f"schema {schema['name']!r} is not a JSON Schema: {e}")
            self.validators[schema["id"]] = validator
        try:
            validator(message)
        except fastjsonschema.JsonSchemaValueException as e:
            raise Fault(f"{what}: the message does not follow schema {schema['name']!r}: "
                        f"{e.message}")

    def define(self, table, record, what):
        old = table.get(record["id"])
        demand(old is None or old == record, f"{what}: id {record['id']} defined twice, differently")
        table[record["id"]] = record

    def message(self, content, what):
        f = Fields(content, what)
        record = {"channel_id": f.u16(), "sequence": f.u32(), "log_time": f.u64(),
                  "publish_time": f.u64()}
        raw = f.rest()
        demand(record["channel_id"] in self.channels,
               f"{what}: message on channel {record['channel_id']} before its Channel record")
        channel = self.channels[record["channel_id"]]
        if channel["message_encoding"] == "json":
            try:
                record["data"] = json.loads(raw.decode("utf-8"))
            except (UnicodeDecodeError, json.JSONDecodeError) as e:
                raise Fault(f"{what}: a json message that is not JSON: {e}")
            self.validate(channel, record["data"], what)
        else:
            record["data_hex"] = raw.hex()
        return record

    def chunk(self, offset, content, length):
        what = f"Chunk at byte {offset}"
        f = Fields(content, what)
        start, end, size, crc = f.u64(), f.u64(), f.u64(), f.u32()
        compression = f.string()
        compressed = f.bytes64()
        f.end()
        inner = decompress(compression, compressed, size, what)
        demand(len(inner) == size, f"{what}: {len(inner)} bytes uncompressed, {size} said")
        demand(crc == 0 or zlib.crc32(inner) == crc, f"{what}: its CRC does not match")
        chunk = {"offset": offset, "length": length, "start": start, "end": end,
                 "compression": compression, "compressed_size": len(compressed),
                 "uncompressed_size": size, "messages": {}, "message_count": 0}
        for at, opcode, body, _ in records(inner, 0, len(inner), what):
            where = f"{what}, inner byte {at}"
            if opcode == 0x03:
                self.define(self.schemas, self.schema(body, where), where)
            elif opcode == 0x04:
                record = self.channel(body, where)
                demand(record["schema_id"] == 0 or record["schema_id"] in self.schemas,
                       f"{where}: channel before its schema")
                self.define(self.channels, record, where)
            elif opcode == 0x05:
                message = self.message(body, where)
                demand(start <= message["log_time"] <= end,
                       f"{where}: log time outside the chunk's [{start}, {end}]")
                chunk["messages"].setdefault(message["channel_id"], []).append(
                    (message["log_time"], at))
                chunk["message_count"] += 1
                message["chunk"] = len(self.chunks)
                self.messages.append(message)
            else:
                raise Fault(f"{where}: record 0x{opcode:02x} inside a chunk")
        if chunk["message_count"] == 0:
            demand(start == 0 and end == 0, f"{what}: no messages but times {start}, {end}")
        else:
            times = [t for entries in chunk["messages"].values() for t, _ in entries]
            demand(start == min(times) and end == max(times),
                   f"{what}: its times are not its messages' first and last")
        self.chunks.append(chunk)

    def message_index(self, offset, content, length):
        what = f"MessageIndex at byte {offset}"
        f = Fields(content, what)
        channel_id = f.u16()
        inner = Fields(f.bytes32(), what)
        entries = []
        while inner.at < len(inner.data):
            entries.append((inner.u64(), inner.u64()))
        f.end()
        return channel_id, entries

    def attachment(self, offset, content, length):
        what = f"Attachment at byte {offset}"
        f = Fields(content, what)
        record = {"offset": offset, "length": length, "log_time": f.u64(),
                  "create_time": f.u64(), "name": f.string(), "media_type": f.string()}
        data = f.bytes64()
        covered = f.at
        crc = f.u32()
        f.end()
        demand(crc == 0 or zlib.crc32(content[:covered]) == crc, f"{what}: its CRC does not match")
        record["data_size"] = len(data)
        try:
            record["data"] = data.decode("utf-8")
        except UnicodeDecodeError:
            record["data_hex"] = data.hex()
        self.attachments.append(record)

    def read_data(self):
        data = self.data
        demand(len(data) >= 8 or self.cut_ok, "shorter than the magic")
        demand(data[:len(MAGIC)] == MAGIC[:len(data)], "does not start with the MCAP magic")
        if len(data) < 8:
            return
        first = True
        pending_index = None  # channels of the last chunk still owed a MessageIndex
        for offset, opcode, content, length in records(data, 8, len(data), "data", self.cut_ok):
            name = OPCODES.get(opcode, f"0x{opcode:02x}")
            what = f"{name} at byte {offset}"
            if first:
                demand(opcode == 0x01, f"the first record is {name}, not Header")
                f = Fields(content, what)
                self.header = {"profile": f.string(), "library": f.string()}
                f.end()
                first = False
                continue
            if opcode != 0x07 and pending_index is not None:
                demand(not pending_index, f"{what}: chunk's message indexes missing for channels "
                       f"{sorted(pending_index)}")
                pending_index = None
            if opcode == 0x03:
                self.define(self.schemas, self.schema(content, what), what)
            elif opcode == 0x04:
                self.define(self.channels, self.channel(content, what), what)
            elif opcode == 0x05:
                raise Fault(f"{what}: a message outside every chunk (this writer chunks them all)")
            elif opcode == 0x06:
                self.chunk(offset, content, length)
                pending_index = set(self.chunks[-1]["messages"])
                self.chunks[-1]["index_offsets"] = {}
                self.chunks[-1]["index_length"] = 0
            elif opcode == 0x07:
                demand(pending_index is not None, f"{what}: not right after a chunk")
                channel_id, entries = self.message_index(offset, content, length)
                chunk = self.chunks[-1]
                demand(channel_id in pending_index,
                       f"{what}: channel {channel_id} has no messages in the chunk, or two indexes")
                pending_index.discard(channel_id)
                demand(sorted(entries) == sorted(chunk["messages"][channel_id]),
                       f"{what}: its entries are not the chunk's messages on channel {channel_id}")
                chunk["index_offsets"][channel_id] = offset
                chunk["index_length"] += length
            elif opcode == 0x09:
                self.attachment(offset, content, length)
            elif opcode == 0x0C:
                f = Fields(content, what)
                self.metadata.append({"offset": offset, "length": length, "name": f.string(),
                                      "metadata": f.string_map()})
                f.end()
            elif opcode == 0x0F:
                f = Fields(content, what)
                crc = f.u32()
                f.end()
                demand(crc == 0 or zlib.crc32(data[:offset]) == crc,
                       f"{what}: the data section's CRC does not match")
                self.data_end = offset + length
                return
            elif opcode == 0x02:
                raise Fault(f"{what}: Footer before DataEnd")
            elif 0x01 <= opcode <= 0x7F:
                raise Fault(f"{what}: {name} is not allowed in the data section")
        demand(self.cut_ok, "the file ends before its DataEnd record")
        demand(not first, "no Header")

    def read_summary(self):
        data = self.data
        demand(len(data) >= 8 + 9 + 20 + 8, "too short for a footer")
        demand(data[-8:] == MAGIC, "does not end with the MCAP magic")
        footer_at = len(data) - 8 - 29
        demand(data[footer_at] == 0x02 and struct.unpack_from("<Q", data, footer_at + 1)[0] == 20,
               "no Footer record before the closing magic")
        summary_start, offset_start, summary_crc = struct.unpack_from("<QQI", data, footer_at + 9)
        demand(summary_start == self.data_end,
               f"the footer's summary_start {summary_start} is not the end of DataEnd {self.data_end}")
        end_of_summary = offset_start if offset_start else footer_at
        demand(summary_start <= end_of_summary <= footer_at, "the summary offsets are out of order")
        demand(summary_crc == 0 or zlib.crc32(data[summary_start:footer_at + 9 + 16]) == summary_crc,
               "the summary's CRC does not match")

        groups = []  # (opcode, start, length) of each run of one opcode
        schemas, channels, chunk_indexes, attachment_indexes, metadata_indexes = {}, {}, [], [], []
        statistics = None
        for offset, opcode, content, length in records(data, summary_start, end_of_summary,
                                                       "summary"):
            what = f"{OPCODES.get(opcode, hex(opcode))} at byte {offset} (summary)"
            demand(opcode in SUMMARY_OPCODES, f"{what}: not allowed in the summary")
            if groups and groups[-1][0] == opcode:
                groups[-1][2] += length
            else:
                demand(all(g[0] != opcode for g in groups), f"{what}: its opcode's group is split")
                groups.append([opcode, offset, length])
            f = Fields(content, what)
            if opcode == 0x03:
                record = self.schema(content, what)
                schemas[record["id"]] = record
                continue
            if opcode == 0x04:
                record = self.channel(content, what)
                channels[record["id"]] = record
                continue
            if opcode == 0x08:
                record = {"start": f.u64(), "end": f.u64(), "offset": f.u64(), "length": f.u64(),
                          "index_offsets": f.u16_u64_map(), "index_length": f.u64(),
                          "compression": f.string(), "compressed_size": f.u64(),
                          "uncompressed_size": f.u64()}
                chunk_indexes.append(record)
            elif opcode == 0x0A:
                record = {"offset": f.u64(), "length": f.u64(), "log_time": f.u64(),
                          "create_time": f.u64(), "data_size": f.u64(), "name": f.string(),
                          "media_type": f.string()}
                attachment_indexes.append(record)
            elif opcode == 0x0B:
                demand(statistics is None, f"{what}: a second Statistics record")
                statistics = {"message_count": f.u64(), "schema_count": f.u16(),
                              "channel_count": f.u32(), "attachment_count": f.u32(),
                              "metadata_count": f.u32(), "chunk_count": f.u32(),
                              "message_start_time": f.u64(), "message_end_time": f.u64(),
                              "channel_message_counts": f.u16_u64_map()}
                demand(0x04 in [g[0] for g in groups], f"{what}: before the Channel records")
            elif opcode == 0x0D:
                metadata_indexes.append({"offset": f.u64(), "length": f.u64(),
                                         "name": f.string()})
            f.end()

        # copies of the data section's schemas and channels, all of them
        demand(schemas == self.schemas, "the summary's schemas are not the data section's")
        demand(channels == self.channels, "the summary's channels are not the data section's")

        # one chunk index per chunk, each pointing at its chunk and its message indexes
        demand(len(chunk_indexes) == len(self.chunks),
               f"{len(chunk_indexes)} chunk indexes for {len(self.chunks)} chunks")
        for index, chunk in zip(chunk_indexes, self.chunks):
            what = f"the chunk index of the chunk at byte {chunk['offset']}"
            for key in ("start", "end", "offset", "length", "index_offsets", "index_length",
                        "compression", "compressed_size", "uncompressed_size"):
                demand(index[key] == chunk[key], f"{what}: {key} {index[key]} is not {chunk[key]}")

        demand(len(attachment_indexes) == len(self.attachments),
               f"{len(attachment_indexes)} attachment indexes for {len(self.attachments)}")
        for index, attachment in zip(attachment_indexes, self.attachments):
            for key in index:
                demand(index[key] == attachment[key],
                       f"the index of attachment {attachment['name']!r}: {key} differs")

        demand(len(metadata_indexes) == len(self.metadata),
               f"{len(metadata_indexes)} metadata indexes for {len(self.metadata)}")
        for index, record in zip(metadata_indexes, self.metadata):
            for key in index:
                demand(index[key] == record[key], f"the index of metadata {record['name']!r}: {key}")

        demand(statistics is not None, "no Statistics record")
        counts = {}
        for message in self.messages:
            counts[message["channel_id"]] = counts.get(message["channel_id"], 0) + 1
        times = [m["log_time"] for m in self.messages]
        expected = {"message_count": len(self.messages), "schema_count": len(self.schemas),
                    "channel_count": len(self.channels),
                    "attachment_count": len(self.attachments),
                    "metadata_count": len(self.metadata), "chunk_count": len(self.chunks),
                    "message_start_time": min(times, default=0),
                    "message_end_time": max(times, default=0),
                    "channel_message_counts": counts}
        for key, value in expected.items():
            demand(statistics[key] == value, f"Statistics: {key} {statistics[key]} is not {value}")
        self.statistics = statistics

        # the summary offsets: one per group, exactly where the group is
        offsets = []
        if offset_start:
            for offset, opcode, content, length in records(data, offset_start, footer_at,
                                                           "summary offsets"):
                demand(opcode == 0x0E, f"record 0x{opcode:02x} among the summary offsets")
                f = Fields(content, "SummaryOffset")
                offsets.append([f.u8(), f.u64(), f.u64()])
                f.end()
        demand(sorted(offsets) == sorted(groups),
               f"the summary offsets {offsets} are not the summary's groups {groups}")

    def read(self):
        self.read_data()
        if hasattr(self, "data_end"):
            if self.cut_ok and (len(self.data) < 8 or self.data[-8:] != MAGIC):
                return
            self.read_summary()
            self.complete = True


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    cut_ok = "--cut-ok" in argv
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    with open(args[0], "rb") as f:
        data = f.read()
    reader = Reader(data, cut_ok)
    try:
        reader.read()
    except Fault as e:
        print(f"{args[0]}: {e}", file=sys.stderr)
        return 1
    chunks = [{k: v for k, v in c.items() if k != "messages"} for c in reader.chunks]
    for c in chunks:
        c["index_offsets"] = {str(k): v for k, v in c.get("index_offsets", {}).items()}
    out = {
        "complete": reader.complete,
        "header": getattr(reader, "header", None),
        "schemas": sorted(reader.schemas.values(), key=lambda s: s["id"]),
        "channels": sorted(reader.channels.values(), key=lambda c: c["id"]),
        "messages": reader.messages,
        "chunks": chunks,
        "attachments": reader.attachments,
        "metadata": reader.metadata,
        "statistics": getattr(reader, "statistics", None),
    }
    if out["statistics"]:
        out["statistics"]["channel_message_counts"] = {
            str(k): v for k, v in out["statistics"]["channel_message_counts"].items()}
    # one write: json.dump writes each token, a system call each when stdout is unbuffered
    sys.stdout.write(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
