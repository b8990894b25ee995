// Writes the MCAP and ULog files of bench/robotics_read.sh, streamed to disk:
//
//   node write_bench_logs.mjs SECONDS RATE_HZ OUT_DIR
//
// OUT_DIR/imu_none.mcap and imu_zstd.mcap: /imu (sensor_msgs/msg/Imu, CDR) by the MCAP project's
// writer (@mcap/core McapWriter, 1 MiB chunks — its default — with a summary) and Foxglove's CDR
// serializer (@foxglove/rosmsg2-serialization), zstd by @foxglove/wasm-zstd;
// OUT_DIR/imu.ulg: sensor_combined at RATE_HZ in the layout of tests/fixtures/write_ulog_fixtures.mjs
// (our writer: no ULog writer is to be had here). Run from a folder whose node_modules holds the
// packages of tests/fixtures/package.json. Values pseudo-random with a fixed seed.
import fs from "node:fs";
import path from "node:path";

import { McapWriter } from "@mcap/core";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";
import { parse } from "@foxglove/rosmsg";
import zstd from "@foxglove/wasm-zstd";

const SEP = "=".repeat(80);
const IMU_DEFINITION = `std_msgs/Header header
geometry_msgs/Quaternion orientation
float64[9] orientation_covariance
geometry_msgs/Vector3 angular_velocity
float64[9] angular_velocity_covariance
geometry_msgs/Vector3 linear_acceleration
float64[9] linear_acceleration_covariance
${SEP}
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
${SEP}
MSG: geometry_msgs/Quaternion
float64 x 0
float64 y 0
float64 z 0
float64 w 1
${SEP}
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
`;
const START_NS = 1700000000123456789n;

function rng(seed) {
  let x = seed >>> 0 || 1;
  const next = () => {
    x ^= x << 13; x >>>= 0; x ^= x >>> 17; x ^= x << 5; x >>>= 0;
    return (x + 0.5) / 4294967296;
  };
  return () => Math.sqrt(-2 * Math.log(next())) * Math.cos(2 * Math.PI * next());
}

/// An @mcap/core IWritable appending to a file.
class FileWritable {
  constructor(file) { this.fd = fs.openSync(file, "w"); this.pos = 0n; }
  position() { return this.pos; }
  async write(buffer) { fs.writeSync(this.fd, buffer); this.pos += BigInt(buffer.length); }
  close() { fs.closeSync(this.fd); }
}

async function writeMcaps(count, rateHz, out) {
  await zstd.isLoaded;
  const imu = new MessageWriter(parse(IMU_DEFINITION, { ros2: true }));
  const files = [
    { name: "imu_none.mcap", compress: undefined },
    { name: "imu_zstd.mcap",
      compress: (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) }) },
  ].map((f) => {
    const writable = new FileWritable(path.join(out, f.name));
    return { writable, writer: new McapWriter({ writable, compressChunk: f.compress }) };
  });
  const ids = [];
  for (const { writer } of files) {
    await writer.start({ profile: "ros2", library: "imunoise bench" });
    const schemaId = await writer.registerSchema({
      name: "sensor_msgs/msg/Imu", encoding: "ros2msg",
      data: new TextEncoder().encode(IMU_DEFINITION),
    });
    ids.push(await writer.registerChannel({
      topic: "/imu", schemaId, messageEncoding: "cdr", metadata: new Map(),
    }));
  }
  const g = rng(7);
  const period = BigInt(Math.round(1e9 / rateHz));
  const msg = {
    header: { stamp: { sec: 0, nanosec: 0 }, frame_id: "imu_link" },
    orientation: { x: 0, y: 0, z: 0, w: 1 },
    orientation_covariance: [-1, 0, 0, 0, 0, 0, 0, 0, 0],
    angular_velocity: { x: 0, y: 0, z: 0 },
    angular_velocity_covariance: [...Array(9).keys()].map((k) => 1e-6 * (k + 1)),
    linear_acceleration: { x: 0, y: 0, z: 0 },
    linear_acceleration_covariance: [...Array(9).keys()].map((k) => 1e-4 * (k + 1)),
  };
  for (let i = 0; i < count; i++) {
    const stamp = START_NS + BigInt(i) * period;
    msg.header.stamp = { sec: Number(stamp / 1000000000n), nanosec: Number(stamp % 1000000000n) };
    msg.angular_velocity = { x: 0.01 * g(), y: 0.01 * g(), z: 0.01 * g() };
    msg.linear_acceleration = { x: 0.02 * g(), y: 0.02 * g(), z: 9.80665 + 0.02 * g() };
    const data = imu.writeMessage(msg);
    const log = stamp + 2500000n;
    for (let k = 0; k < files.length; k++) {
      await files[k].writer.addMessage({
        channelId: ids[k], sequence: i, logTime: log, publishTime: log, data,
      });
    }
  }
  for (const f of files) { await f.writer.end(); f.writable.close(); }
}

const COMBINED = "uint64_t timestamp;float[3] gyro_rad;uint32_t gyro_integral_dt;" +
  "int32_t accelerometer_timestamp_relative;float[3] accelerometer_m_s2;" +
  "uint32_t accelerometer_integral_dt;uint8_t accelerometer_clipping;uint8_t gyro_clipping;" +
  "uint8_t accel_calibration_count;uint8_t gyro_calibration_count;";

function writeUlog(count, rateHz, out) {
  const fd = fs.openSync(path.join(out, "imu.ulg"), "w");
  const message = (type, body) => {
    const h = Buffer.alloc(3);
    h.writeUInt16LE(body.length, 0);
    h.write(type, 2, "latin1");
    return Buffer.concat([h, body]);
  };
  const head = Buffer.alloc(16);
  Buffer.from([0x55, 0x4c, 0x6f, 0x67, 0x01, 0x12, 0x35, 0x01]).copy(head);
  head.writeBigUInt64LE(10000000n, 8);
  const sub = Buffer.alloc(3);
  fs.writeSync(fd, Buffer.concat([head, message("B", Buffer.alloc(40)),
    message("F", Buffer.from(`sensor_combined:${COMBINED}`, "latin1")),
    message("A", Buffer.concat([sub, Buffer.from("sensor_combined", "latin1")]))]));
  const g = rng(8);
  const periodUs = 1e6 / rateHz;
  const block = 4096;
  const record = 3 + 2 + 48;
  const buf = Buffer.alloc(block * record);
  for (let i0 = 0; i0 < count; i0 += block) {
    const n = Math.min(block, count - i0);
    buf.fill(0);
    for (let j = 0; j < n; j++) {
      const o = j * record;
      buf.writeUInt16LE(50, o);
      buf.write("D", o + 2, "latin1");
      buf.writeUInt16LE(0, o + 3);
      const b = o + 5;
      buf.writeBigUInt64LE(10000000n + BigInt(Math.round((i0 + j) * periodUs)), b);
      for (let k = 0; k < 3; k++) buf.writeFloatLE(0.01 * g(), b + 8 + 4 * k);
      buf.writeUInt32LE(Math.round(periodUs), b + 20);
      for (let k = 0; k < 3; k++) buf.writeFloatLE((k === 2 ? -9.80665 : 0) + 0.02 * g(), b + 28 + 4 * k);
      buf.writeUInt32LE(Math.round(periodUs), b + 40);
    }
    fs.writeSync(fd, buf, 0, n * record);
  }
  fs.closeSync(fd);
}

if (process.argv.length !== 5) {
  console.error("usage: node write_bench_logs.mjs SECONDS RATE_HZ OUT_DIR");
  process.exit(2);
}
const count = Math.round(Number(process.argv[2]) * Number(process.argv[3]));
writeUlog(count, Number(process.argv[3]), process.argv[4]);
await writeMcaps(count, Number(process.argv[3]), process.argv[4]);
