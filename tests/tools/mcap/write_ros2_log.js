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
//   (--detections pointcloud2: /radar/SENSOR/points, sensor_msgs/msg/PointCloud2 (CDR) instead, as
//                       ROS 2 radar drivers publish: fields x, y, z, radial_speed, rcs (float32,
//                       little-endian); --cloud-layout mixed: big-endian, x y z float64, a uint8
//                       "flags", radial_speed float32, rcs float64, 40-byte points, 2 rows with 8
//                       bytes of padding each, NaN points filling the last row, is_dense false;
//                       --scan-frame vehicle (with --ego tf): the points in "base_link", not the
//                       radar's frame);
//   (--box-frame vehicle: each entity in "base_link" where an ego row has its time);
// --storage sqlite3|mcap [--split N]: OUT is a ROS 2 bag directory as `ros2 bag record` writes it
// (metadata.yaml, N storage files: SQLite written by the sqlite3 command in Humble's layout, or
// MCAP); only CDR topics go in (use --boxes openlabel).
// --attachment-mib N attaches N MiB of bytes to the log (before its messages).
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
const { execFileSync } = require("child_process");

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

const POINT_CLOUD2 = `std_msgs/Header header
uint32 height
uint32 width
sensor_msgs/PointField[] fields
bool is_bigendian
uint32 point_step
uint32 row_step
uint8[] data
bool is_dense
${HEADER_DEFINITIONS}
================================================================================
MSG: sensor_msgs/PointField
uint8 INT8=1
uint8 UINT8=2
uint8 INT16=3
uint8 UINT16=4
uint8 INT32=5
uint8 UINT32=6
uint8 FLOAT32=7
uint8 FLOAT64=8
string name
uint32 offset
uint8 datatype
uint32 count`;

// A PointCloud2 of the returns, in the layout asked for (x, y, z moved by X_FS into the frame F).
function pointCloud2(header, returns, layout, X_FS) {
  const pts = returns.map((r) => {
    const ground = r.range * Math.cos(r.elevation);
    const [xs, ys, zs] = [ground * Math.cos(r.azimuth), ground * Math.sin(r.azimuth), r.range * Math.sin(r.elevation)];
    const [x, y, z] = X_FS ? X_FS(xs, ys, zs) : [xs, ys, zs];
    return { x, y, z, v: r.doppler_velocity, a: r.amplitude };
  });
  if (layout !== "mixed") {
    const data = Buffer.alloc(20 * pts.length);
    pts.forEach((p, k) => [p.x, p.y, p.z, p.v, p.a].forEach((v, j) => data.writeFloatLE(v, 20 * k + 4 * j)));
    return { header, height: 1, width: pts.length, is_bigendian: false, point_step: 20, row_step: 20 * pts.length, data, is_dense: true,
      fields: ["x", "y", "z", "radial_speed", "rcs"].map((name, j) => ({ name, offset: 4 * j, datatype: 7, count: 1 })) };
  }
  const width = Math.floor(pts.length / 2) + 1, step = 40, rowStep = width * step + 8;
  const data = Buffer.alloc(2 * rowStep);
  for (let k = 0; k < 2 * width; ++k) {
    const p = k < pts.length ? pts[k] : { x: NaN, y: NaN, z: NaN, v: NaN, a: NaN };
    const at = Math.floor(k / width) * rowStep + (k % width) * step;
    data.writeDoubleBE(p.x, at), data.writeDoubleBE(p.y, at + 8), data.writeDoubleBE(p.z, at + 16);
    data.writeUInt8(7, at + 24), data.writeFloatBE(p.v, at + 28), data.writeDoubleBE(p.a, at + 32);
  }
  return { header, height: 2, width, is_bigendian: true, point_step: step, row_step: rowStep, data, is_dense: false,
    fields: [["x", 0, 8], ["y", 8, 8], ["z", 16, 8], ["flags", 24, 2], ["radial_speed", 28, 7], ["rcs", 32, 8]]
      .map(([name, offset, datatype]) => ({ name, offset, datatype, count: 1 })) };
}

// A ROS 2 bag directory: metadata.yaml and the storage files, the messages (in log order) split
// into `split` files by count.
function writeBag(out, storage, split, topics, messages, writeMcapFile) {
  fs.mkdirSync(out, { recursive: true });
  const per = Math.ceil(messages.length / split);
  const files = [];
  for (let f = 0; f < split; ++f) {
    const part = messages.slice(f * per, (f + 1) * per);
    const name = `${path.basename(out)}_${f}.${storage === "sqlite3" ? "db3" : "mcap"}`;
    files.push({ name, part });
    if (storage === "mcap") {
      writeMcapFile(path.join(out, name), part);
      continue;
    }
    const sql = ["PRAGMA journal_mode=OFF;", "BEGIN;",
      "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);",
      "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);",
      "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"];
    topics.forEach((t, i) => sql.push(`INSERT INTO topics VALUES(${i + 1}, '${t.topic}', '${t.type}', 'cdr', '');`));
    part.forEach((m, i) => sql.push(`INSERT INTO messages VALUES(${i + 1}, ${m.topicIndex + 1}, ${m.logNs}, X'${Buffer.from(m.data).toString("hex")}');`));
    sql.push("COMMIT;");
    execFileSync("sqlite3", [path.join(out, name)], { input: sql.join("\n") });
  }
  const yaml = ["rosbag2_bagfile_information:", "  version: 5", `  storage_identifier: ${storage}`,
    "  duration:", `    nanoseconds: ${messages.length ? messages[messages.length - 1].logNs - messages[0].logNs : 0}`,
    "  starting_time:", `    nanoseconds_since_epoch: ${messages.length ? messages[0].logNs : 0}`,
    `  message_count: ${messages.length}`, "  topics_with_message_count:",
    ...topics.flatMap((t, i) => ["    - topic_metadata:", `        name: ${t.topic}`, `        type: ${t.type}`,
      "        serialization_format: cdr", "        offered_qos_profiles: \"\"",
      `      message_count: ${messages.filter((m) => m.topicIndex === i).length}`]),
    "  compression_format: \"\"", "  compression_mode: \"\"", "  relative_file_paths:", ...files.map((f) => `    - ${f.name}`),
    "  files:", ...files.flatMap((f) => [`    - path: ${f.name}`, `      message_count: ${f.part.length}`])];
  fs.writeFileSync(path.join(out, "metadata.yaml"), yaml.join("\n") + "\n");
}

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
  const o = { compression: "none", mapping: "", chunkBytes: 64 * 1024, detections: "radarscan", ego: "odometry", boxes: "scene", scanDelayMs: 0,
    cloudLayout: "float32", scanFrame: "radar", boxFrame: "world", storage: "", split: 1, attachmentMib: 0 };
  for (let i = 4; i < argv.length; i += 2) {
    if (argv[i] === "--compression") o.compression = argv[i + 1];
    else if (argv[i] === "--mapping") o.mapping = argv[i + 1];
    else if (argv[i] === "--chunk-bytes") o.chunkBytes = Number(argv[i + 1]);
    else if (argv[i] === "--detections") o.detections = argv[i + 1];
    else if (argv[i] === "--ego") o.ego = argv[i + 1];
    else if (argv[i] === "--boxes") o.boxes = argv[i + 1];
    else if (argv[i] === "--scan-delay-ms") o.scanDelayMs = Number(argv[i + 1]);
    else if (argv[i] === "--cloud-layout") o.cloudLayout = argv[i + 1];
    else if (argv[i] === "--scan-frame") o.scanFrame = argv[i + 1];
    else if (argv[i] === "--box-frame") o.boxFrame = argv[i + 1];
    else if (argv[i] === "--storage") o.storage = argv[i + 1];
    else if (argv[i] === "--split") o.split = Number(argv[i + 1]);
    else if (argv[i] === "--attachment-mib") o.attachmentMib = Number(argv[i + 1]);
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
  const topicOf = (id) => (o.detections === "pointcloud" || o.detections === "pointcloud2" ? `/radar/${id}/points` : `/radar/${id}/scan`);
  const returnsOf = cycles.map(() => []);
  const cycleIndex = (t) => (rec.clock === "per_sensor" ? Number(t.cycle) : Number(t.cycle) * rec.sensors.length +
    rec.sensors.findIndex((s) => s.id === t.sensor));
  for (const t of targets) {
    const el = t.elevation_rad === undefined ? 0 : Number(t.elevation_rad);
    returnsOf[cycleIndex(t)].push({ range: Number(t.range_m) / Math.cos(el), azimuth: Number(t.azimuth_rad), elevation: el,
      doppler_velocity: Number(t.range_rate_mps), amplitude: Number(t.amplitude_db) });
  }

  const clouds = o.detections === "pointcloud", clouds2 = o.detections === "pointcloud2";
  // A writer with every schema and channel registered in one order (so that a bag's files share
  // channel ids); `topics` lists the channels' topics and types in that order.
  const topics = [];
  const openWriter = async () => {
    const chunks = [];
    const writable = { position: () => BigInt(chunks.reduce((n, c) => n + c.length, 0)), write: async (b) => { chunks.push(Buffer.from(b)); } };
    const compressChunk = o.compression === "zstd" ? (d) => ({ compression: "zstd", compressedData: zstd.compress(d, 3) })
      : o.compression === "lz4" ? (d) => ({ compression: "lz4", compressedData: Buffer.from(lz4.compress(d)) })
      : undefined;
    const writer = new McapWriter({ writable, chunkSize: o.chunkBytes, compressChunk });
    await writer.start({ profile: "ros2", library: "rcsim tests/tools/mcap/write_ros2_log.js" });
    topics.length = 0;
    const channel = async (topic, schemaId, encoding, type, metadata = new Map()) => {
      const id = await writer.registerChannel({ topic, schemaId, messageEncoding: encoding, metadata });
      topics.push({ topic, type, id });
      return id;
    };
    const scanSchema = await writer.registerSchema({ name: "radar_msgs/msg/RadarScan", encoding: "ros2msg", data: Buffer.from(RADAR_SCAN) });
    const odomSchema = await writer.registerSchema({ name: "nav_msgs/msg/Odometry", encoding: "ros2msg", data: Buffer.from(ODOMETRY) });
    const sceneSchema = await writer.registerSchema({ name: "foxglove.SceneUpdate", encoding: "jsonschema",
      data: Buffer.from(JSON.stringify(foxglove.SceneUpdate)) });
    const cloudSchema = clouds ? await writer.registerSchema({ name: "foxglove.PointCloud", encoding: "jsonschema",
      data: Buffer.from(JSON.stringify(foxglove.PointCloud)) }) : 0;
    const cloud2Schema = clouds2 ? await writer.registerSchema({ name: "sensor_msgs/msg/PointCloud2", encoding: "ros2msg",
      data: Buffer.from(POINT_CLOUD2) }) : 0;
    const ids = { scan: {} };
    for (const sensor of rec.sensors) {
      ids.scan[sensor.id] = clouds ? await channel(topicOf(sensor.id), cloudSchema, "json", "foxglove.PointCloud")
        : clouds2 ? await channel(topicOf(sensor.id), cloud2Schema, "cdr", "sensor_msgs/msg/PointCloud2")
        : await channel(topicOf(sensor.id), scanSchema, "cdr", "radar_msgs/msg/RadarScan");
    }
    ids.odom = await channel("/odom", odomSchema, "cdr", "nav_msgs/msg/Odometry");
    const tfSchema = await writer.registerSchema({ name: "tf2_msgs/msg/TFMessage", encoding: "ros2msg", data: Buffer.from(TF_MESSAGE) });
    ids.tf = await channel("/tf", tfSchema, "cdr", "tf2_msgs/msg/TFMessage");
    ids.tfStatic = await channel("/tf_static", tfSchema, "cdr", "tf2_msgs/msg/TFMessage",
      new Map([["offered_qos_profiles", "durability: transient_local"]]));
    ids.scene = await channel("/annotations", sceneSchema, "json", "foxglove.SceneUpdate");
    return { writer, chunks, ids };
  };
  const first = await openWriter();
  const scanChannel = first.ids.scan, odomChannel = first.ids.odom, tfChannel = first.ids.tf, tfStaticChannel = first.ids.tfStatic;
  const sceneChannel = first.ids.scene;
  const scanWriter = new MessageWriter(parseMessageDefinition(RADAR_SCAN, { ros2: true }));
  const odomWriter = new MessageWriter(parseMessageDefinition(ODOMETRY, { ros2: true }));
  const cloud2Writer = new MessageWriter(parseMessageDefinition(POINT_CLOUD2, { ros2: true }));
  const tfWriter = new MessageWriter(parseMessageDefinition(TF_MESSAGE, { ros2: true }));
  const topicOfChannel = (id) => topics.findIndex((t) => t.id === id);
  // A radar's points moved from its frame into base_link (--scan-frame vehicle): its /tf_static mounting.
  const mountingOf = (id) => {
    const s = rec.sensors.find((x) => x.id === id);
    const [c, sn] = [Math.cos(s.yaw_rad), Math.sin(s.yaw_rad)];
    return (x, y, z) => [s.x_m + c * x - sn * y, s.y_m + sn * x + c * y, 0.5 + z];
  };

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
        : clouds2 ? cloud2Writer.writeMessage(pointCloud2({ stamp: stampOf(ns), frame_id: o.scanFrame === "vehicle" ? "base_link" : c.sensor },
          returnsOf[i], o.cloudLayout, o.scanFrame === "vehicle" ? mountingOf(c.sensor) : null))
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
      let [x, y, yaw, frame] = [Number(b.x_m), Number(b.y_m), Number(b.yaw_rad), "odom"];
      const e = egoAt.get(t);
      if (o.boxFrame === "vehicle" && e) {  // X_VO = X_WV^-1 X_WO
        const [dx, dy, ey] = [x - Number(e.x_m), y - Number(e.y_m), Number(e.yaw_rad)];
        [x, y, yaw, frame] = [Math.cos(ey) * dx + Math.sin(ey) * dy, -Math.sin(ey) * dx + Math.cos(ey) * dy, yaw - ey, "base_link"];
      }
      return { timestamp: stampOf(ns), frame_id: frame, id: b.object, lifetime: { sec: 0, nsec: 0 }, frame_locked: false,
        metadata: [{ key: "class", value: ob.class }, { key: "speed_mps", value: b.speed_mps }],
        arrows: [], cubes: [{ pose: { position: { x, y, z: 0.75 }, orientation: quaternionOfYaw(yaw) },
          size: { x: ob.length_m, y: ob.width_m, z: 1.5 }, color: { r: 0.2, g: 0.4, b: 1, a: 0.5 } }],
        spheres: [], cylinders: [], lines: [], triangles: [], texts: [], models: [] };
    });
    messages.push({ ns, order: 2, channelId: sceneChannel,
      data: Buffer.from(JSON.stringify({ deletions: [], entities: entities.map((e) => ({ ...e, timestamp: { sec: e.timestamp.sec, nsec: e.timestamp.nanosec } })) })) });
  }
  messages.forEach((m) => { if (m.logNs === undefined) m.logNs = m.ns; });
  messages.sort((a, b) => (a.logNs < b.logNs ? -1 : a.logNs > b.logNs ? 1 : a.order - b.order));
  const writeMcapFile = async (file, list, w) => {
    const { writer, chunks } = w || (await openWriter());
    if (o.attachmentMib > 0) {  // a calibration blob a recorder attached, as big as asked
      await writer.addAttachment({ name: "calibration.bin", logTime: 0n, createTime: 0n, mediaType: "application/octet-stream",
        data: new Uint8Array(o.attachmentMib * 1024 * 1024).fill(7) });
    }
    let sequence = 0;
    for (const m of list) {
      await writer.addMessage({ channelId: m.channelId, sequence: sequence++, logTime: m.logNs, publishTime: m.logNs, data: m.data });
    }
    await writer.end();
    fs.writeFileSync(file, Buffer.concat(chunks));
    return chunks.reduce((n, c) => n + c.length, 0);
  };
  let bytes = 0;
  if (o.storage) {
    messages.forEach((m) => (m.topicIndex = topicOfChannel(m.channelId)));
    const bagTopics = topics.filter((t) => t.type !== "foxglove.SceneUpdate" && t.type !== "foxglove.PointCloud");
    if (messages.some((m) => !bagTopics.includes(topics[m.topicIndex]))) throw new Error("a bag holds CDR topics only: use --boxes openlabel");
    const files = [];
    writeBag(out, o.storage, o.split, topics, messages, (file, part) => files.push([file, part]));
    for (const [file, part] of files) bytes += await writeMcapFile(file, part);
  } else {
    bytes = await writeMcapFile(out, messages, first);
  }
  if (o.mapping) {
    const mapping = { format: "rcsim-mcap-mapping", version: 1, name: rec.name,
      sensors: rec.sensors.map((s) => ({ id: s.id, topic: topicOf(s.id), type: s.type,
        ...(o.ego === "tf" ? {} : { x_m: s.x_m, y_m: s.y_m, yaw_rad: s.yaw_rad }), reports: s.reports || "tracks",
        ...(o.scanFrame === "vehicle" ? { frame: s.id } : {}),
        ...(clouds2 ? { fields: { range_rate: "radial_speed", amplitude: "rcs" } } : {}) })),
      ego: o.ego === "tf" ? { tf: { world_frame: "odom", vehicle_frame: "base_link" } } : { topic: "/odom" },
      objects: o.boxes === "openlabel" ? { openlabel: path.basename(out) + ".openlabel.json" } : { topic: "/annotations" } };
    fs.writeFileSync(o.mapping, JSON.stringify(mapping, null, 2) + "\n");
    if (o.boxes === "openlabel") fs.writeFileSync(path.join(path.dirname(o.mapping), path.basename(out) + ".openlabel.json"), JSON.stringify(openlabel));
  }
  console.log(JSON.stringify({ messages: messages.length, cycles: cycles.length, bytes }));
}

main().catch((e) => {
  console.error(e.stack || String(e));
  process.exit(1);
});
