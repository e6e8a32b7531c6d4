// Decodes a telear recording with the reference reader (npm's @mcap/core, indexed) and every
// message with the file's OWN schemas (each Schema record's FileDescriptorSet, through
// @mcap/support's protobufFromBinaryDescriptor -- what Foxglove does), and prints a summary as
// one JSON document for tests/record/session_recorder_test.cpp:
//
//   node decode_recording.mjs FILE.mcap
//
// {"topics": {TOPIC: {"schema", "count", "first", "last"}},   first/last: decoded messages
//  "frames": {TOPIC: [child_frame_id, ...]},                   /tf's frames, each once
//  "events": [text, ...], "plan_events": [[kind, text], ...],
//  "jpeg_ok": {TOPIC: bool},                                    every image a JPEG (FF D8 .. FF D9)
//  "attachments": [name, ...], "metadata": {NAME: {...}}, "error": "..." on failure}
// Bytes fields are summarised by their length; 64-bit integers are printed as strings.

import { open } from "node:fs/promises";

import { McapIndexedReader } from "@mcap/core";
import { FileHandleReadable } from "@mcap/nodejs";
import { loadDecompressHandlers, protobufFromBinaryDescriptor } from "@mcap/support";

const summarise = (object) =>
  JSON.parse(
    JSON.stringify(object, (key, value) => {
      if (value instanceof Uint8Array) return { bytes: value.length };
      if (typeof value === "bigint") return value.toString();
      return value;
    }),
  );

async function main() {
  const path = process.argv[2];
  const handle = await open(path, "r");
  const out = {
    topics: {},
    frames: {},
    events: [],
    plan_events: [],
    jpeg_ok: {},
    attachments: [],
    metadata: {},
  };
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle),
      decompressHandlers: await loadDecompressHandlers(),
    });
    const types = new Map();
    for (const [id, channel] of reader.channelsById) {
      const schema = reader.schemasById.get(channel.schemaId);
      if (schema.encoding !== "protobuf") throw new Error(`${channel.topic}: ${schema.encoding}`);
      const root = protobufFromBinaryDescriptor(schema.data);
      types.set(id, { type: root.lookupType(schema.name), topic: channel.topic, name: schema.name });
      out.topics[channel.topic] = { schema: schema.name, count: 0 };
    }
    for await (const message of reader.readMessages()) {
      const { type, topic } = types.get(message.channelId);
      const decoded = type.toObject(type.decode(message.data), {
        longs: String,
        enums: String,
        defaults: true,
      });
      const entry = out.topics[topic];
      entry.count += 1;
      if (entry.count === 1) entry.first = summarise(decoded);
      entry.last = summarise(decoded);
      if (type.fullName === ".foxglove.CompressedImage") {
        const d = decoded.data;
        const ok =
          d.length > 4 && d[0] === 0xff && d[1] === 0xd8 && d[d.length - 2] === 0xff &&
          d[d.length - 1] === 0xd9;
        out.jpeg_ok[topic] = (out.jpeg_ok[topic] ?? true) && ok;
      } else if (type.fullName === ".foxglove.FrameTransforms") {
        const frames = new Set(out.frames[topic] ?? []);
        for (const t of decoded.transforms) frames.add(`${t.parent_frame_id}>${t.child_frame_id}`);
        out.frames[topic] = [...frames].sort();
      } else if (type.fullName === ".foxglove.Log") {
        out.events.push(decoded.message);
      } else if (type.fullName === ".telear.record.v1.PlanEvent") {
        out.plan_events.push([decoded.kind, decoded.text]);
      }
    }
    for await (const attachment of reader.readAttachments()) out.attachments.push(attachment.name);
    for await (const metadata of reader.readMetadata()) {
      out.metadata[metadata.name] = Object.fromEntries(metadata.metadata);
    }
  } catch (error) {
    out.error = String(error?.stack ?? error);
  } finally {
    await handle.close();
  }
  process.stdout.write(JSON.stringify(out) + "\n");
}

await main();
