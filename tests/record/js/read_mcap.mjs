// Reads MCAP files with the reference reader, npm's @mcap/core (Foxglove's), and prints what it
// found as one JSON document, for telear's writer tests (tests/record/mcap_reference_test.cpp)
// to compare with what they wrote.
//
//   node read_mcap.mjs [--expect EXPECT.json] FILE.mcap [FILE.mcap ...]
//
// Each file is read twice:
//   indexed -- McapIndexedReader: footer, summary offsets and summary (summary CRC checked),
//              then every message through the chunk indexes and message indexes, attachments
//              and metadata through their indexes; the data section's CRC is recomputed here.
//   stream  -- McapStreamReader from the first byte to the last, as a reader of a file whose
//              writer died would: records are returned while they are complete, and the reader
//              stops (without an error) at a record cut short. `complete` says whether it saw
//              the footer and closing magic.
// An error of either reader is reported in its `error` field, with what it read before it.
//
// EXPECT.json (written by the C++ test) lists the messages as
//   {"messages": [{"topic", "sequence", "log_time", "publish_time", "sha256"}, ...]}
// (times as decimal strings: they are 64-bit); each message read is looked up by topic and
// sequence and its times and bytes compared. `mismatches` counts those that differ, `unknown`
// those not expected, `duplicates` those read twice.

import { createHash } from "node:crypto";
import { open, readFile } from "node:fs/promises";

import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { FileHandleReadable } from "@mcap/nodejs";
import { loadDecompressHandlers } from "@mcap/support";

// CRC-32 (IEEE, reflected; the one MCAP uses), written here rather than taken from the
// writer's C++ so that a wrong polynomial or bit order on one side shows.
const crcTable = new Uint32Array(256).map((_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});
function crc32(bytes) {
  let c = 0xffffffff;
  for (let i = 0; i < bytes.length; i++) c = crcTable[(c ^ bytes[i]) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

const sha256 = (bytes) => createHash("sha256").update(bytes).digest("hex");
const text = (bytes) => Buffer.from(bytes).toString("utf8");

// Message tally of one reader: per topic count and log time range, checked against EXPECT.
class Tally {
  constructor(expected) {
    this.expected = expected;
    this.seen = new Set();
    this.topics = {};
    this.messages = 0;
    this.mismatches = 0;
    this.unknown = 0;
    this.duplicates = 0;
    this.firstProblems = [];
  }
  problem(kind, detail) {
    if (this.firstProblems.length < 5) this.firstProblems.push(`${kind}: ${detail}`);
  }
  add(topic, message) {
    this.messages++;
    const t = (this.topics[topic] ??= { count: 0, first_log_time: null, last_log_time: null });
    t.count++;
    if (t.first_log_time === null || message.logTime < BigInt(t.first_log_time)) {
      t.first_log_time = message.logTime.toString();
    }
    if (t.last_log_time === null || message.logTime > BigInt(t.last_log_time)) {
      t.last_log_time = message.logTime.toString();
    }
    if (!this.expected) return;
    const key = `${topic}#${message.sequence}`;
    if (this.seen.has(key)) {
      this.duplicates++;
      this.problem("duplicate", key);
      return;
    }
    this.seen.add(key);
    const want = this.expected.get(key);
    if (!want) {
      this.unknown++;
      this.problem("unknown", key);
    } else if (
      want.log_time !== message.logTime.toString() ||
      want.publish_time !== message.publishTime.toString() ||
      want.sha256 !== sha256(message.data)
    ) {
      this.mismatches++;
      this.problem("mismatch", key);
    }
  }
  json() {
    return {
      messages: this.messages,
      topics: this.topics,
      mismatches: this.mismatches,
      unknown: this.unknown,
      duplicates: this.duplicates,
      problems: this.firstProblems,
    };
  }
}

const mapToObject = (map) => Object.fromEntries([...map].map(([k, v]) => [k, v]));

async function readIndexed(path, decompressHandlers, expected) {
  const out = {};
  const tally = new Tally(expected);
  const handle = await open(path, "r");
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle),
      decompressHandlers,
    });
    out.header = { profile: reader.header.profile, library: reader.header.library };
    out.schemas = [...reader.schemasById.values()].map((s) => ({
      id: s.id,
      name: s.name,
      encoding: s.encoding,
      sha256: sha256(s.data),
    }));
    out.channels = [...reader.channelsById.values()].map((c) => ({
      id: c.id,
      schema_id: c.schemaId,
      topic: c.topic,
      message_encoding: c.messageEncoding,
      metadata: mapToObject(c.metadata),
    }));
    const s = reader.statistics;
    if (s) {
      const byTopic = {};
      for (const [id, count] of s.channelMessageCounts) {
        byTopic[reader.channelsById.get(id)?.topic ?? `#${id}`] = count.toString();
      }
      out.statistics = {
        message_count: s.messageCount.toString(),
        schema_count: s.schemaCount,
        channel_count: s.channelCount,
        attachment_count: s.attachmentCount,
        metadata_count: s.metadataCount,
        chunk_count: s.chunkCount,
        message_start_time: s.messageStartTime.toString(),
        message_end_time: s.messageEndTime.toString(),
        channel_message_counts: byTopic,
      };
    }
    out.chunk_indexes = reader.chunkIndexes.length;
    out.chunk_compression = [...new Set(reader.chunkIndexes.map((c) => c.compression))];
    // The data section's CRC: @mcap/core reads it from the Data End record but does not check it.
    const bytes = await readFile(path);
    const computed = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
    out.data_section_crc_ok = reader.dataSectionCrc === computed;

    let lastLogTime = -1n;
    out.log_time_ordered = true;
    for await (const message of reader.readMessages()) {
      if (message.logTime < lastLogTime) out.log_time_ordered = false;
      lastLogTime = message.logTime;
      tally.add(reader.channelsById.get(message.channelId).topic, message);
    }
    out.attachments = [];
    for await (const a of reader.readAttachments()) {
      out.attachments.push({
        name: a.name,
        media_type: a.mediaType,
        log_time: a.logTime.toString(),
        create_time: a.createTime.toString(),
        sha256: sha256(a.data),
      });
    }
    out.metadata = [];
    for await (const m of reader.readMetadata()) {
      out.metadata.push({ name: m.name, metadata: mapToObject(m.metadata) });
    }
  } catch (error) {
    out.error = String(error?.message ?? error);
  } finally {
    await handle.close();
  }
  return Object.assign(out, tally.json());
}

async function readStream(path, decompressHandlers, expected) {
  const out = { schemas: [], attachments: [], metadata: [], chunks: 0, complete: false };
  const tally = new Tally(expected);
  const channels = new Map();
  const reader = new McapStreamReader({ decompressHandlers, includeChunks: true });
  try {
    // In pieces, as a reader following a growing file gets it.
    const bytes = await readFile(path);
    for (let at = 0; at < bytes.length; at += 1 << 16) {
      reader.append(bytes.subarray(at, Math.min(bytes.length, at + (1 << 16))));
      for (let record; (record = reader.nextRecord()); ) {
        switch (record.type) {
          case "Schema":
            if (!out.schemas.includes(record.name)) out.schemas.push(record.name);
            break;
          case "Channel":
            channels.set(record.id, record);
            break;
          case "Chunk":
            out.chunks++;
            break;
          case "Message":
            tally.add(channels.get(record.channelId).topic, record);
            break;
          case "Attachment":
            out.attachments.push({ name: record.name, sha256: sha256(record.data) });
            break;
          case "Metadata":
            out.metadata.push({ name: record.name, metadata: mapToObject(record.metadata) });
            break;
          case "DataEnd":
            out.data_end = true;
            break;
        }
      }
    }
    out.complete = reader.done();
    out.bytes_left = reader.bytesRemaining();
  } catch (error) {
    out.error = String(error?.message ?? error);
  }
  return Object.assign(out, tally.json());
}

async function main() {
  const args = process.argv.slice(2);
  let expected = null;
  const files = [];
  for (let i = 0; i < args.length; i++) {
    if (args[i] === "--expect") {
      const doc = JSON.parse(text(await readFile(args[++i])));
      expected = new Map(doc.messages.map((m) => [`${m.topic}#${m.sequence}`, m]));
    } else {
      files.push(args[i]);
    }
  }
  if (files.length === 0) {
    process.stderr.write("usage: node read_mcap.mjs [--expect EXPECT.json] FILE.mcap...\n");
    process.exit(2);
  }
  const decompressHandlers = await loadDecompressHandlers();
  const results = [];
  for (const file of files) {
    results.push({
      file,
      indexed: await readIndexed(file, decompressHandlers, expected),
      stream: await readStream(file, decompressHandlers, expected),
    });
  }
  process.stdout.write(JSON.stringify({ reader: "@mcap/core", files: results }, null, 1) + "\n");
}

await main();
