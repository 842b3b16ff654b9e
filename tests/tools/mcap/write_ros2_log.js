// node write_ros2_log.js RECORDING_DIR OUT.mcap [--compression none|zstd|lz4] [--mapping OUT.json]
//   [--chunk-bytes N] [--detections radarscan|pointcloud] [--ego odometry|tf] [--boxes scene|openlabel]
//   [--scan-delay-ms N]
// Test tool: writes an rcsim recording (schemas/recording.md) as a ROS 2 log, the way a user's
// drive arrives, with the format's own writer (@mcap/core) and ROS 2's CDR (@foxglove/cdr through
// @foxglove/rosmsg2-serialization):
//   /radar/SENSOR/scan  radar_msgs/msg/RadarScan, one per sensor cycle, stamped with its time; each
//                       return's range the slant range (the recording's horizontal range over the
//                       cosine of its elevation), float32 as the message has it;
//   (--detections pointcloud: /radar/SENSOR/points, foxglove.PointCloud (JSON) instead: float32
//                       fields x, y, z in the radar's frame, range_rate and amplitude);
//   /odom               nav_msgs/msg/Odometry, one per ego row (pose in "odom", twist in "base_link");
//   (--ego tf: /tf, tf2_msgs/msg/TFMessage, instead: "base_footprint" in "odom" per ego row, and
//                       /tf_static: "base_link" 0.3 m above "base_footprint", each radar's frame
//                       (its id) mounted in "base_link"; the mapping then gives no mountings);
//   /annotations        foxglove.SceneUpdate (JSON), one per annotation time: a cube per box, its
//                       class and speed in the entity's metadata.
//   (--boxes openlabel: no /annotations; OUT.openlabel.json beside the mapping instead, an ASAM
//                       OpenLABEL 1.0 file: a frame per annotation time stamped "sec.nanosec", each
//                       box a 10-value cuboid in the vehicle's frame "base_link" where an ego row has
//                       its time (else in "odom"), its speed a num "speed_mps".)
// --scan-delay-ms N logs every 7th scan N ms late (its log time, not its stamp), as a loaded
// recorder does: the log's order is then not the stamps' order.
// Times are nanoseconds: the recording's source.first_timestamp_ns (else 1.7e18) + t_s. With
// --mapping, also writes the rcsim-mcap-mapping file (schemas/mcap-mapping.md) that imports it.
"use strict";
const fs = require("fs");
const path = require("path");
const { McapWriter } = require("@mcap/core");
const { parse: parseMessageDefinition } = require("@foxglove/rosmsg");
const { MessageWriter } = require("@foxglove/rosmsg2-serialization");
const foxglove = require("@foxglove/schemas/jsonschema");
const zstd = require("@foxglove/wasm-zstd");
const lz4 = require("lz4js");

// The definitions a ROS 2 message with a std_msgs/Header appends (the bag's concatenated form).
const HEADER_DEFINITIONS = `================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec`;

const VECTOR3_DEFINITION = `================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z`;
const QUATERNION_DEFINITION = `================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w`;

const RADAR_SCAN = `std_msgs/Header header
radar_msgs/RadarReturn[] returns
${HEADER_DEFINITIONS}
================================================================================
MSG: radar_msgs/RadarReturn
float32 range
float32 azimuth
float32 elevation
float32 doppler_velocity
float32 amplitude`;

const ODOMETRY = `std_msgs/Header header
string child_frame_id
geometry_msgs/PoseWithCovariance pose
geometry_msgs/TwistWithCovariance twist
${HEADER_DEFINITIONS}
================================================================================
MSG: geometry_msgs/PoseWithCovariance
geometry_msgs/Pose pose
float64[36] covariance
================================================================================
MSG: geometry_msgs/Pose
geometry_msgs/Point position
geometry_msgs/Quaternion orientation
================================================================================
MSG: geometry_msgs/Point
float64 x
float64 y
float64 z
${QUATERNION_DEFINITION}
================================================================================
MSG: geometry_msgs/TwistWithCovariance
geometry_msgs/Twist twist
float64[36] covariance
================================================================================
MSG: geometry_msgs/Twist
geometry_msgs/Vector3 linear
geometry_msgs/Vector3 angular
${VECTOR3_DEFINITION}`;

const TF_MESSAGE = `geometry_msgs/TransformStamped[] transforms
================================================================================
MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
geometry_msgs/Transform transform
${HEADER_DEFINITIONS}
================================================================================
MSG: geometry_msgs/Transform
geometry_msgs/Vector3 translation
geometry_msgs/Quaternion rotation
${VECTOR3_DEFINITION}
${QUATERNION_DEFINITION}`;

function readCsv(file) {
  const lines = fs.readFileSync(file, "utf8").split("\n").filter((l) => l.length > 0);
  const header = lines[0].split(",");
  return lines.slice(1).map((l) => {
    const fields = l.split(",");
    const row = {};
    header.forEach((h, i) => (row[h] = fields[i]));
    return row;
  });
}

function options(argv) {
  const o = { compression: "none", mapping: "", chunkBytes: 64 * 1024, detections: "radarscan", ego: "odometry", boxes: "scene", scanDelayMs: 0 };
  for (let i = 4; i < argv.length; i += 2) {
    if (argv[i] === "--compression") o.compression = argv[i + 1];
    else if (argv[i] === "--mapping") o.mapping = argv[i + 1];
    else if (argv[i] === "--chunk-bytes") o.chunkBytes = Number(argv[i + 1]);
    else if (argv[i] === "--detections") o.detections = argv[i + 1];
    else if (argv[i] === "--ego") o.ego = argv[i + 1];
    else if (argv[i] === "--boxes") o.boxes = argv[i + 1];
    else if (argv[i] === "--scan-delay-ms") o.scanDelayMs = Number(argv[i + 1]);
    else throw new Error(`unknown option ${argv[i]}`);
  }
  return o;
}

function stampOf(ns) {
  return { sec: Number(ns / 1000000000n), nanosec: Number(ns % 1000000000n) };
}

function quaternionOfYaw(yaw) {
  return { x: 0, y: 0, z: Math.sin(yaw / 2), w: Math.cos(yaw / 2) };
}

async function main() {
  const [dir, out] = [process.argv[2], process.argv[3]];
  const o = options(process.argv);
  await zstd.isLoaded;
  const rec = JSON.parse(fs.readFileSync(path.join(dir, "recording.json"), "utf8"));
  const firstNs = BigInt((rec.source && rec.source.first_timestamp_ns) || "1700000000000000000");
  const nsOf = (t) => firstNs + BigInt(Math.round(Number(t) * 1e6)) * 1000n;  // files carry microseconds
  const ego = readCsv(path.join(dir, "ego.csv"));
  const boxes = readCsv(path.join(dir, "objects.csv"));
  const targets = readCsv(path.join(dir, "targets.csv"));
  // Every sensor cycle: cycles.csv's rows (own clocks), else every sensor at every ego row.
  const cycles = [];
  if (rec.clock === "per_sensor") {
    readCsv(path.join(dir, "cycles.csv")).forEach((c) => cycles.push({ t: c.t_s, sensor: c.sensor }));
  } else {
    ego.forEach((e) => rec.sensors.forEach((s) => cycles.push({ t: e.t_s, sensor: s.id })));
  }
  const returnsOf = cycles.map(() => []);
  const cycleIndex = (t) => (rec.clock === "per_sensor" ? Number(t.cycle) : Number(t.cycle) * rec.sensors.length +
    rec.sensors.findIndex((s) => s.id === t.sensor));
  for (const t of targets) {
    const el = t.elevation_rad === undefined ? 0 : Number(t.elevation_rad);
    returnsOf[cycleIndex(t)].push({ range: Number(t.range_m) / Math.cos(el), azimuth: Number(t.azimuth_rad), elevation: el,
      doppler_velocity: Number(t.range_rate_mps), amplitude: Number(t.amplitude_db) });
  }

  const chunks = [];
  const writable = { position: () => BigInt(chunks.reduce((n, c) => n + c.length, 0)), write: async (b) => { chunks.push(Buffer.from(b)); } };
  const compressChunk = o.compression === "zstd" ? (d) => ({ compression: "zstd", compressedData: zstd.compress(d, 3) })
    : o.compression === "lz4" ? (d) => ({ compression: "lz4", compressedData: Buffer.from(lz4.compress(d)) })
    : undefined;
  const writer = new McapWriter({ writable, chunkSize: o.chunkBytes, compressChunk });
  await writer.start({ profile: "ros2", library: "rcsim tests/tools/mcap/write_ros2_log.js" });
  const scanSchema = await writer.registerSchema({ name: "radar_msgs/msg/RadarScan", encoding: "ros2msg",
    data: Buffer.from(RADAR_SCAN) });
  const odomSchema = await writer.registerSchema({ name: "nav_msgs/msg/Odometry", encoding: "ros2msg",
    data: Buffer.from(ODOMETRY) });
  const sceneSchema = await writer.registerSchema({ name: "foxglove.SceneUpdate", encoding: "jsonschema",
    data: Buffer.from(JSON.stringify(foxglove.SceneUpdate)) });
  const scanWriter = new MessageWriter(parseMessageDefinition(RADAR_SCAN, { ros2: true }));
  const odomWriter = new MessageWriter(parseMessageDefinition(ODOMETRY, { ros2: true }));
  const clouds = o.detections === "pointcloud";
  const cloudSchema = clouds ? await writer.registerSchema({ name: "foxglove.PointCloud", encoding: "jsonschema",
    data: Buffer.from(JSON.stringify(foxglove.PointCloud)) }) : 0;
  const topicOf = (id) => (clouds ? `/radar/${id}/points` : `/radar/${id}/scan`);
  const scanChannel = {};
  for (const s of rec.sensors) {
    scanChannel[s.id] = await writer.registerChannel({ topic: topicOf(s.id), schemaId: clouds ? cloudSchema : scanSchema,
      messageEncoding: clouds ? "json" : "cdr", metadata: new Map() });
  }
  const odomChannel = await writer.registerChannel({ topic: "/odom", schemaId: odomSchema, messageEncoding: "cdr", metadata: new Map() });
  const tfSchema = await writer.registerSchema({ name: "tf2_msgs/msg/TFMessage", encoding: "ros2msg", data: Buffer.from(TF_MESSAGE) });
  const tfWriter = new MessageWriter(parseMessageDefinition(TF_MESSAGE, { ros2: true }));
  const tfChannel = await writer.registerChannel({ topic: "/tf", schemaId: tfSchema, messageEncoding: "cdr", metadata: new Map() });
  const tfStaticChannel = await writer.registerChannel({ topic: "/tf_static", schemaId: tfSchema, messageEncoding: "cdr",
    metadata: new Map([["offered_qos_profiles", "durability: transient_local"]]) });
  const sceneChannel = await writer.registerChannel({ topic: "/annotations", schemaId: sceneSchema, messageEncoding: "json",
    metadata: new Map() });

  // Every message with its time, written in time order (scans, then odometry, then boxes at one time).
  const messages = [];
  const cloudOf = (ns, frame, returns) => {
    const data = Buffer.alloc(20 * returns.length);
    returns.forEach((r, k) => {
      const ground = r.range * Math.cos(r.elevation);
      [ground * Math.cos(r.azimuth), ground * Math.sin(r.azimuth), r.range * Math.sin(r.elevation), r.doppler_velocity, r.amplitude]
        .forEach((v, j) => data.writeFloatLE(v, 20 * k + 4 * j));
    });
    const stamp = stampOf(ns);
    return Buffer.from(JSON.stringify({ timestamp: { sec: stamp.sec, nsec: stamp.nanosec }, frame_id: frame,
      pose: { position: { x: 0, y: 0, z: 0 }, orientation: { x: 0, y: 0, z: 0, w: 1 } }, point_stride: 20,
      fields: ["x", "y", "z", "range_rate", "amplitude"].map((name, j) => ({ name, offset: 4 * j, type: 7 })),
      data: data.toString("base64") }));
  };
  cycles.forEach((c, i) => {
    const ns = nsOf(c.t);
    messages.push({ ns, logNs: ns + (i % 7 === 3 ? BigInt(o.scanDelayMs) * 1000000n : 0n), order: 0, channelId: scanChannel[c.sensor],
      data: clouds ? cloudOf(ns, c.sensor, returnsOf[i])
        : scanWriter.writeMessage({ header: { stamp: stampOf(ns), frame_id: c.sensor }, returns: returnsOf[i] }) });
  });
  const transform = (ns, parent, child, x, y, z, yaw) => ({ header: { stamp: stampOf(ns), frame_id: parent }, child_frame_id: child,
    transform: { translation: { x, y, z }, rotation: quaternionOfYaw(yaw) } });
  if (o.ego === "tf") {
    const ns = nsOf(ego[0].t_s);
    messages.push({ ns, order: -1, channelId: tfStaticChannel, data: tfWriter.writeMessage({ transforms: [
      transform(ns, "base_footprint", "base_link", 0, 0, 0.3, 0),
      ...rec.sensors.map((s) => transform(ns, "base_link", s.id, s.x_m, s.y_m, 0.5, s.yaw_rad))] }) });
  }
  for (const e of ego) {
    const ns = nsOf(e.t_s);
    if (o.ego === "tf") {
      messages.push({ ns, order: 1, channelId: tfChannel, data: tfWriter.writeMessage({ transforms: [
        transform(ns, "odom", "base_footprint", Number(e.x_m), Number(e.y_m), 0, Number(e.yaw_rad))] }) });
      continue;
    }
    messages.push({ ns, order: 1, channelId: odomChannel, data: odomWriter.writeMessage({
      header: { stamp: stampOf(ns), frame_id: "odom" }, child_frame_id: "base_link",
      pose: { pose: { position: { x: Number(e.x_m), y: Number(e.y_m), z: 0 }, orientation: quaternionOfYaw(Number(e.yaw_rad)) },
        covariance: new Array(36).fill(0) },
      twist: { twist: { linear: { x: Number(e.speed_mps), y: 0, z: 0 }, angular: { x: 0, y: 0, z: Number(e.yaw_rate_radps) } },
        covariance: new Array(36).fill(0) } }) });
  }
  const classOf = new Map(rec.objects.map((ob) => [ob.id, ob]));
  const byTime = new Map();
  for (const b of boxes) {
    if (!byTime.has(b.t_s)) byTime.set(b.t_s, []);
    byTime.get(b.t_s).push(b);
  }
  // The boxes as OpenLABEL: in the vehicle's frame, X_VO = X_WV^-1 X_WO, where the ego has a row then.
  const egoAt = new Map(ego.map((e) => [e.t_s, e]));
  const openlabel = { openlabel: { metadata: { schema_version: "1.0.0" }, objects: {}, frames: {},
    coordinate_systems: { odom: { type: "scene_cs", parent: "", children: ["base_link"] },
      base_link: { type: "local_cs", parent: "odom", children: [] } } } };
  if (o.boxes === "openlabel") {
    for (const ob of rec.objects) openlabel.openlabel.objects[ob.id] = { name: ob.id, type: ob.class };
    let frame = 0;
    for (const [t, list] of byTime) {
      const ns = nsOf(t);
      const objects = {};
      for (const b of list) {
        const ob = classOf.get(b.object);
        let [x, y, yaw, cs] = [Number(b.x_m), Number(b.y_m), Number(b.yaw_rad), "odom"];
        const e = egoAt.get(t);
        if (e) {
          const [dx, dy, ey] = [x - Number(e.x_m), y - Number(e.y_m), Number(e.yaw_rad)];
          [x, y, yaw, cs] = [Math.cos(ey) * dx + Math.sin(ey) * dy, -Math.sin(ey) * dx + Math.cos(ey) * dy, yaw - ey, "base_link"];
        }
        const q = quaternionOfYaw(yaw);
        objects[b.object] = { object_data: { cuboid: [{ name: "box", coordinate_system: cs,
          val: [x, y, 0.75, q.x, q.y, q.z, q.w, ob.length_m, ob.width_m, 1.5] }],
          num: [{ name: "speed_mps", val: Number(b.speed_mps) }] } };
      }
      openlabel.openlabel.frames[String(frame++)] = { frame_properties: { timestamp: `${ns / 1000000000n}.${String(ns % 1000000000n).padStart(9, "0")}` },
        objects };
    }
  }
  for (const [t, list] of o.boxes === "openlabel" ? [] : byTime) {
    const ns = nsOf(t);
    const entities = list.map((b) => {
      const ob = classOf.get(b.object);
      return { timestamp: stampOf(ns), frame_id: "odom", id: b.object, lifetime: { sec: 0, nsec: 0 }, frame_locked: false,
        metadata: [{ key: "class", value: ob.class }, { key: "speed_mps", value: b.speed_mps }],
        arrows: [], cubes: [{ pose: { position: { x: Number(b.x_m), y: Number(b.y_m), z: 0.75 }, orientation: quaternionOfYaw(Number(b.yaw_rad)) },
          size: { x: ob.length_m, y: ob.width_m, z: 1.5 }, color: { r: 0.2, g: 0.4, b: 1, a: 0.5 } }],
        spheres: [], cylinders: [], lines: [], triangles: [], texts: [], models: [] };
    });
    messages.push({ ns, order: 2, channelId: sceneChannel,
      data: Buffer.from(JSON.stringify({ deletions: [], entities: entities.map((e) => ({ ...e, timestamp: { sec: e.timestamp.sec, nsec: e.timestamp.nanosec } })) })) });
  }
  messages.forEach((m) => { if (m.logNs === undefined) m.logNs = m.ns; });
  messages.sort((a, b) => (a.logNs < b.logNs ? -1 : a.logNs > b.logNs ? 1 : a.order - b.order));
  let sequence = 0;
  for (const m of messages) {
    await writer.addMessage({ channelId: m.channelId, sequence: sequence++, logTime: m.logNs, publishTime: m.logNs, data: m.data });
  }
  await writer.end();
  fs.writeFileSync(out, Buffer.concat(chunks));
  if (o.mapping) {
    const mapping = { format: "rcsim-mcap-mapping", version: 1, name: rec.name,
      sensors: rec.sensors.map((s) => ({ id: s.id, topic: topicOf(s.id), type: s.type,
        ...(o.ego === "tf" ? {} : { x_m: s.x_m, y_m: s.y_m, yaw_rad: s.yaw_rad }), reports: s.reports || "tracks" })),
      ego: o.ego === "tf" ? { tf: { world_frame: "odom", vehicle_frame: "base_link" } } : { topic: "/odom" },
      objects: o.boxes === "openlabel" ? { openlabel: path.basename(out) + ".openlabel.json" } : { topic: "/annotations" } };
    fs.writeFileSync(o.mapping, JSON.stringify(mapping, null, 2) + "\n");
    if (o.boxes === "openlabel") fs.writeFileSync(path.join(path.dirname(o.mapping), path.basename(out) + ".openlabel.json"), JSON.stringify(openlabel));
  }
  console.log(JSON.stringify({ messages: messages.length, cycles: cycles.length, bytes: chunks.reduce((n, c) => n + c.length, 0) }));
}

main().catch((e) => {
  console.error(e.stack || String(e));
  process.exit(1);
});
