// node check_mcap.js FILE.mcap: reads FILE with @mcap/core's indexed reader (footer, summary and
// its CRC, chunk and message indexes) and its stream reader (every record, CRCs checked), parses
// every JSON message and checks those under a foxglove.* schema name against Foxglove's published
// JSON schema of that name, and the others against the JSON Schema the file itself gives them. Prints one JSON line: chunks, schemas, messages per topic, the first
// problems; exits 1 if there is any.
"use strict";
const fs = require("fs");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const foxglove = require("@foxglove/schemas/jsonschema");
const Ajv = require("ajv");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");

// The chunk compressions rcsim reads (and writes: zstd), as Foxglove's own reader takes them.
const decompressHandlers = {
  zstd: (data, size) => zstd.decompress(data, Number(size)),
  lz4: (data) => Buffer.from(lz4.decompress(data)),
};

async function main() {
  await zstd.isLoaded;
  const bytes = fs.readFileSync(process.argv[2]);
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, length) => bytes.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const ajv = new Ajv({ strict: false, allErrors: false });
  const validators = new Map();
  const problems = [];
  const counts = {};
  const decoder = new TextDecoder();
  for await (const m of reader.readMessages()) {
    const channel = reader.channelsById.get(m.channelId);
    const schema = reader.schemasById.get(channel.schemaId);
    counts[channel.topic] = (counts[channel.topic] || 0) + 1;
    let body;
    try {
      body = JSON.parse(decoder.decode(m.data));
    } catch (e) {
      problems.push(`${channel.topic}: not JSON: ${e.message}`);
      continue;
    }
    // A schema of the file's own (rcsim.*): its JSON Schema as written in the file.
    if (!schema.name.startsWith("foxglove.")) {
      if (schema.encoding !== "jsonschema") continue;
      if (!validators.has(schema.name)) validators.set(schema.name, ajv.compile(JSON.parse(decoder.decode(schema.data))));
      const own = validators.get(schema.name);
      if (!own(body) && problems.length < 10) problems.push(`${channel.topic}: ${ajv.errorsText(own.errors)}`);
      continue;
    }
    const name = schema.name.slice("foxglove.".length);
    if (!validators.has(name)) {
      if (!foxglove[name]) {
        problems.push(`${channel.topic}: Foxglove has no schema ${schema.name}`);
        validators.set(name, null);
      } else {
        validators.set(name, ajv.compile(foxglove[name]));
      }
    }
    const validate = validators.get(name);
    if (validate && !validate(body) && problems.length < 10) {
      problems.push(`${channel.topic}: ${ajv.errorsText(validate.errors)}`);
    }
  }
  const stream = new McapStreamReader({ validateCrcs: true, decompressHandlers });
  stream.append(bytes);
  let streamed = 0;
  for (let record; (record = stream.nextRecord()); ) if (record.type === "Message") streamed++;
  if (!stream.done()) problems.push("the stream reader did not reach the end");
  const schemas = [...reader.schemasById.values()].map((s) => `${s.name}:${s.encoding}`);
  console.log(JSON.stringify({ chunks: reader.chunkIndexes.length, schemas, counts, streamed, problems }));
  process.exit(problems.length === 0 ? 0 : 1);
}

main().catch((e) => {
  console.log(JSON.stringify({ problems: [`unreadable: ${e.message}`] }));
  process.exit(1);
});
