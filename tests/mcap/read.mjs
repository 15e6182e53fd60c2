// Reads an MCAP file of sensor_msgs/msg/PointCloud2 messages with the reference reader (npm's
// @mcap/core), decodes each message's CDR by hand and prints its points.
//
// Usage: node read.mjs FILE.mcap NODE_MODULES_PARENT
//   NODE_MODULES_PARENT: the directory whose node_modules holds @mcap/core (tests/mcap/install.sh).
//
// Checks on the way (any failure: a message on stderr, exit status 1):
//   - McapIndexedReader opens the file from its footer and summary (summary CRC checked) and reads
//     every message through the chunk index (each chunk's CRC checked);
//   - McapStreamReader reads the whole file start to end (chunk CRCs checked) and finds the same
//     messages; the Data End's data_section_crc equals the CRC-32 of every byte before it;
//   - profile ros2, one schema sensor_msgs/msg/PointCloud2 (ros2msg, the definition starting with
//     PointCloud2.msg and holding the three MSG: sections), channel encoding cdr;
//   - the CDR: encapsulation 00 01 00 00, height 1, the ten fields of PointXYZIRCAEDT, point_step
//     32, row_step and data length 32 * width, is_bigendian false, is_dense true, nothing after.
// Output (stdout), per message in sequence order: a line "M,sequence,stamp_ns,frame_id,width,topic,
// log_time", then one line per point "P,channel,return_type,intensity,x,y,z,azimuth,elevation,
// distance,time_ns" (time_ns = stamp + time_stamp), written as it is decoded.
import { readFileSync, writeSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";

const [file, modulesParent] = process.argv.slice(2);
if (!file || !modulesParent) {
  console.error("usage: node read.mjs FILE.mcap NODE_MODULES_PARENT");
  process.exit(2);
}
const require = createRequire(path.resolve(modulesParent) + "/");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { crc32 } = require("@foxglove/crc");

function fail(message) {
  console.error(`read.mjs: ${file}: ${message}`);
  process.exit(1);
}
function expect(cond, message) {
  if (!cond) fail(message);
}

const bytes = new Uint8Array(readFileSync(file));
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};

// The PointXYZIRCAEDT fields: name, offset, datatype (UINT8 2, UINT16 4, UINT32 6, FLOAT32 7), count 1.
const FIELDS = [
  ["x", 0, 7], ["y", 4, 7], ["z", 8, 7], ["intensity", 12, 2], ["return_type", 13, 2], ["channel", 14, 4],
  ["azimuth", 16, 7], ["elevation", 20, 7], ["distance", 24, 7], ["time_stamp", 28, 6],
];

// Little-endian CDR; alignment counts from after the 4-byte encapsulation header.
class Cdr {
  constructor(data) {
    this.data = data;
    this.view = new DataView(data.buffer, data.byteOffset, data.byteLength);
    expect(data[0] === 0 && data[1] === 1 && data[2] === 0 && data[3] === 0, "CDR encapsulation is not 00 01 00 00");
    this.pos = 4;
  }
  align(n) {
    while ((this.pos - 4) % n !== 0) this.pos++;
  }
  u8() {
    expect(this.pos + 1 <= this.data.length, "CDR ends early");
    return this.data[this.pos++];
  }
  u32() {
    this.align(4);
    expect(this.pos + 4 <= this.data.length, "CDR ends early");
    const v = this.view.getUint32(this.pos, true);
    this.pos += 4;
    return v;
  }
  i32() {
    const v = this.u32();
    return v | 0;
  }
  str() {
    const n = this.u32();
    expect(n >= 1 && this.pos + n <= this.data.length && this.data[this.pos + n - 1] === 0, "bad CDR string");
    const s = new TextDecoder().decode(this.data.subarray(this.pos, this.pos + n - 1));
    this.pos += n;
    return s;
  }
}

function decodeCloud(data) {
  const c = new Cdr(data);
  const sec = c.i32();
  const nanosec = c.u32();
  const frameId = c.str();
  const height = c.u32();
  const width = c.u32();
  const nfields = c.u32();
  const fields = [];
  for (let i = 0; i < nfields; i++) fields.push([c.str(), c.u32(), c.u8(), c.u32()]);
  const isBigendian = c.u8();
  const pointStep = c.u32();
  const rowStep = c.u32();
  const dataLength = c.u32();
  const start = c.pos;
  expect(start + dataLength + 1 === data.length, `data length ${dataLength} and is_dense do not end the message`);
  const isDense = data[start + dataLength];
  expect(height === 1, `height ${height}`);
  expect(isBigendian === 0, "is_bigendian");
  expect(isDense === 1, "is_dense");
  expect(pointStep === 32 && rowStep === 32 * width && dataLength === rowStep, "point_step/row_step/data length");
  expect(nfields === FIELDS.length, `${nfields} fields`);
  FIELDS.forEach(([name, offset, type], i) => {
    const [n, o, t, count] = fields[i];
    expect(n === name && o === offset && t === type && count === 1, `field ${i}: ${n} ${o} ${t} ${count}`);
  });
  const stamp = BigInt(sec) * 1000000000n + BigInt(nanosec);
  const view = new DataView(data.buffer, data.byteOffset + start, dataLength);
  const rows = [];
  const print = () => {
    writeSync(1, rows.join("\n") + "\n");
    rows.length = 0;
  };
  for (let i = 0; i < width; i++) {
    const b = i * 32;
    const f = (o) => view.getFloat32(b + o, true);
    rows.push(
      [
        "P", view.getUint16(b + 14, true), view.getUint8(b + 13), view.getUint8(b + 12), f(0), f(4), f(8), f(16), f(20), f(24),
        stamp + BigInt(view.getUint32(b + 28, true)),
      ].join(","),
    );
    if (rows.length === 4096) print();
  }
  if (rows.length > 0) print();
}

// The header fields of a PointCloud2, for the M line (the points are printed by decodeCloud).
function cloudHeader(data) {
  const c = new Cdr(data);
  const sec = c.i32();
  const nanosec = c.u32();
  const frameId = c.str();
  c.u32();
  const width = c.u32();
  return { stamp: BigInt(sec) * 1000000000n + BigInt(nanosec), frameId, width };
}

const reader = await McapIndexedReader.Initialize({ readable });
expect(reader.header.profile === "ros2", `profile '${reader.header.profile}'`);
expect(reader.schemasById.size === 1, `${reader.schemasById.size} schemas`);
const schema = [...reader.schemasById.values()][0];
const definition = new TextDecoder().decode(schema.data);
expect(schema.name === "sensor_msgs/msg/PointCloud2" && schema.encoding === "ros2msg", `schema ${schema.name} ${schema.encoding}`);
const rule = "\n" + "=".repeat(80) + "\nMSG: ";
expect(definition.startsWith("# This message holds a collection of N-dimensional points"), "definition: PointCloud2.msg first");
for (const dep of ["sensor_msgs/PointField\n", "std_msgs/Header\n", "builtin_interfaces/Time\n"])
  expect(definition.includes(rule + dep), `definition lacks MSG: ${dep.trim()}`);
for (const channel of reader.channelsById.values())
  expect(channel.messageEncoding === "cdr" && channel.schemaId === schema.id, `channel ${channel.topic}`);
const stats = reader.statistics;
expect(stats !== undefined, "no Statistics record");

// The data section CRC: every byte before the Data End record.
expect(reader.dataSectionCrc !== undefined, "no data_section_crc");
const dataCrc = crc32(bytes.subarray(0, Number(reader.dataEndOffset)));
expect(dataCrc === reader.dataSectionCrc, `data_section_crc ${reader.dataSectionCrc}, computed ${dataCrc}`);

// Start to end with the stream reader: the same messages.
const streamed = new Map();  // by sequence (the indexed reader yields log_time order)
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(bytes);
// In file order: log times never go back, across every topic; one rosbag2 metadata record.
let lastLogTime = -1n;
const rosbag2 = [];
for (let record; (record = stream.nextRecord()); ) {
  if (record.type === "Metadata") rosbag2.push(record);
  if (record.type !== "Message") continue;
  const key = `${record.channelId}/${record.sequence}`;
  expect(!streamed.has(key), `two messages of sequence ${record.sequence} on channel ${record.channelId}`);
  expect(record.logTime >= lastLogTime, `message ${key}: log_time ${record.logTime} before the previous message's`);
  lastLogTime = record.logTime;
  streamed.set(key, record);
}
expect(rosbag2.length === 1 && rosbag2[0].name === "rosbag2" && rosbag2[0].metadata.get("ROS_DISTRO") === "humble",
       "no rosbag2 metadata record with ROS_DISTRO humble");
expect(reader.metadataIndexes.length === 1 && reader.metadataIndexes[0].name === "rosbag2",
       "the summary does not index the rosbag2 metadata record");
expect(stream.done(), "the stream reader did not reach the trailing magic");

const messages = [];
for await (const m of reader.readMessages({ validateCrcs: true })) {
  const s = streamed.get(`${m.channelId}/${m.sequence}`);
  expect(s && s.sequence === m.sequence && s.logTime === m.logTime && Buffer.compare(s.data, m.data) === 0,
         `message ${messages.length}: the stream reader reads another`);
  messages.push(m);
}
const count = messages.length;
expect(count === streamed.size, `indexed reader: ${count} messages, stream reader: ${streamed.size}`);
expect(BigInt(count) === stats.messageCount, `statistics: ${stats.messageCount} messages, read ${count}`);
expect(stats.chunkCount === reader.chunkIndexes.length, "statistics chunk_count");
messages.sort((a, b) => a.sequence - b.sequence);
for (const m of messages) {
  const h = cloudHeader(m.data);
  expect(m.publishTime === m.logTime, `message ${m.sequence}: publish_time is not log_time`);
  const topic = reader.channelsById.get(m.channelId).topic;
  writeSync(1, ["M", m.sequence, h.stamp, h.frameId, h.width, topic, m.logTime].join(",") + "\n");
  decodeCloud(m.data);
}
console.error(`read.mjs: ${file}: ${count} messages in ${reader.chunkIndexes.length} chunks`);
