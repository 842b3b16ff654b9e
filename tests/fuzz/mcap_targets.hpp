#pragma once
// Fuzz entry point of the MCAP importer (`rcsim import --from mcap`, docs/importers.md,
// docs/fuzzing.md). The input is an MCAP file, imported with a fixed mapping (one radar on
// /radar/front/scan, the ego on /odom, boxes on /annotations); what the importer accepts it writes
// as a recording, which rcsim must then read back. The seeds are small logs in that layout made by
// rcsim's own MCAP writer with hand-laid CDR (radar_msgs/RadarScan, nav_msgs/Odometry) and
// foxglove.SceneUpdate JSON: the fuzzer mutates records, chunks, CRCs, CDR and JSON alike.
#include <cmath>
#include <cstring>
#include <sstream>

#include "fuzz/fuzz_support.hpp"
#include "io/mcap_writer.hpp"
#include "io/recording.hpp"
#include "replay/import/mcap_importer.hpp"

namespace rcsim::fuzz {

inline constexpr const char* kMcapMapping = R"({"format": "rcsim-mcap-mapping", "version": 1, "name": "fuzz",
  "sensors": [{"id": "front", "topic": "/radar/front/scan", "type": "srr24", "x_m": 3.7, "y_m": 0.0, "yaw_rad": 0.0}],
  "ego": {"topic": "/odom"}, "objects": {"topic": "/annotations"}})";

inline void fuzz_mcap(Input data) {
  const std::filesystem::path dir = fresh_dir("mcap");
  write_file(dir / "log.mcap", as_text(data));
  write_file(dir / "mapping.json", kMcapMapping);
  replay::DatasetImportOptions options;
  options.mapping = dir / "mapping.json";
  refusals_are_fine([&] {
    const replay::DatasetRecording imported = replay::import_mcap(dir / "log.mcap", options);
    write_recording(dir / "recording", imported.recording);
    try {
      (void)read_recording(dir / "recording");
    } catch (const InputError& e) {
      throw Finding(std::string("rcsim import --from mcap wrote a recording rcsim cannot read: ") + e.what());
    }
  });
}

namespace mcap_seed {

template <typename T>
void put(std::string& out, T value) {
  const std::size_t pad = (sizeof(T) - (out.size() - 4) % sizeof(T)) % sizeof(T);  // aligned from after the header
  out.append(pad, '\0');
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

inline std::string header(std::int64_t t_ns, const std::string& frame) {
  std::string b("\x00\x01\x00\x00", 4);
  put(b, static_cast<std::int32_t>(t_ns / 1'000'000'000));
  put(b, static_cast<std::uint32_t>(t_ns % 1'000'000'000));
  put(b, static_cast<std::uint32_t>(frame.size() + 1));
  b += frame + '\0';
  return b;
}

// A parked car 20 m ahead seen at three points, the ego creeping forward at 1 m/s.
inline std::string radar_scan(std::int64_t t_ns, double ego_x_m) {
  std::string b = header(t_ns, "front");
  put(b, std::uint32_t{3});
  for (int i = 0; i < 3; ++i) {
    const double y_m = -0.6 + 0.6 * i, x_m = 20.0 - ego_x_m - 3.7;
    for (const float v : {static_cast<float>(std::hypot(x_m, y_m)), static_cast<float>(std::atan2(y_m, x_m)), 0.01f, -1.0f, 30.0f}) put(b, v);
  }
  return b;
}

inline std::string odometry(std::int64_t t_ns, double x_m) {
  std::string b = header(t_ns, "odom");
  put(b, std::uint32_t{10});
  b += std::string("base_link") + '\0';
  for (const double v : {x_m, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0}) put(b, v);
  for (int i = 0; i < 36; ++i) put(b, 0.0);
  for (const double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0}) put(b, v);
  for (int i = 0; i < 36; ++i) put(b, 0.0);
  return b;
}

inline std::string scene_update(std::int64_t t_ns) {
  return R"({"deletions": [], "entities": [{"timestamp": {"sec": )" + std::to_string(t_ns / 1'000'000'000) + R"(, "nsec": )" +
         std::to_string(t_ns % 1'000'000'000) +
         R"(}, "frame_id": "odom", "id": "car", "metadata": [{"key": "class", "value": "passenger_car"}], "cubes": [{"pose": )"
         R"({"position": {"x": 22.0, "y": 0.0, "z": 0.75}, "orientation": {"x": 0, "y": 0, "z": 1, "w": 0}}, "size": )"
         R"({"x": 4.5, "y": 1.8, "z": 1.5}}]}]})";
}

// The same three points as a foxglove.PointCloud (float32 x, y, z, range_rate, amplitude).
inline std::string point_cloud(std::int64_t t_ns, double ego_x_m) {
  std::string data;
  for (int i = 0; i < 3; ++i) {
    for (const float v : {static_cast<float>(20.0 - ego_x_m - 3.7), static_cast<float>(-0.6 + 0.6 * i), 0.2f, -1.0f, 30.0f}) {
      char raw[4];
      std::memcpy(raw, &v, 4);
      data.append(raw, 4);
    }
  }
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string base64;
  for (std::size_t i = 0; i < data.size(); i += 3) {  // 60 bytes: whole groups of 3
    const std::uint32_t v = (static_cast<std::uint8_t>(data[i]) << 16) | (static_cast<std::uint8_t>(data[i + 1]) << 8) |
                            static_cast<std::uint8_t>(data[i + 2]);
    for (int k = 3; k >= 0; --k) base64 += kAlphabet[(v >> (6 * k)) & 63];
  }
  std::string fields;
  for (int j = 0; j < 5; ++j) {
    static const char* kNames[] = {"x", "y", "z", "range_rate", "amplitude"};
    fields += std::string(j == 0 ? "" : ", ") + R"({"name": ")" + kNames[j] + R"(", "offset": )" + std::to_string(4 * j) + R"(, "type": 7})";
  }
  return R"({"timestamp": {"sec": )" + std::to_string(t_ns / 1'000'000'000) + R"(, "nsec": )" + std::to_string(t_ns % 1'000'000'000) +
         R"(}, "frame_id": "front", "pose": {"position": {"x": 0, "y": 0, "z": 0}, "orientation": {"x": 0, "y": 0, "z": 0, "w": 1}}, )"
         R"("point_stride": 20, "fields": [)" + fields + R"(], "data": ")" + base64 + R"("})";
}

// The same three points as a sensor_msgs/msg/PointCloud2 (float32 x, y, z, range_rate, amplitude,
// little-endian, one row).
inline std::string point_cloud2(std::int64_t t_ns, double ego_x_m) {
  std::string b = header(t_ns, "front");
  put(b, std::uint32_t{1});  // height
  put(b, std::uint32_t{3});  // width
  put(b, std::uint32_t{5});  // fields
  for (int j = 0; j < 5; ++j) {
    static const char* kNames[] = {"x", "y", "z", "range_rate", "amplitude"};
    put(b, static_cast<std::uint32_t>(std::strlen(kNames[j]) + 1));
    b += std::string(kNames[j]) + '\0';
    put(b, static_cast<std::uint32_t>(4 * j));
    put(b, std::uint8_t{7});  // FLOAT32
    put(b, std::uint32_t{1});
  }
  put(b, std::uint8_t{0});     // is_bigendian
  put(b, std::uint32_t{20});   // point_step
  put(b, std::uint32_t{60});   // row_step
  put(b, std::uint32_t{60});   // data
  for (int i = 0; i < 3; ++i) {
    for (const float v : {static_cast<float>(20.0 - ego_x_m - 3.7), static_cast<float>(-0.6 + 0.6 * i), 0.2f, -1.0f, 30.0f}) put(b, v);
  }
  put(b, std::uint8_t{1});  // is_dense
  return b;
}

}  // namespace mcap_seed

// Logs of 10 radar cycles at 20 Hz, odometry at 10 Hz and boxes at 10 Hz: the radar's as
// RadarScan, as foxglove.PointCloud, as sensor_msgs/msg/PointCloud2, and under another schema.
inline std::vector<std::pair<std::string, std::vector<std::uint8_t>>> mcap_seeds() {
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> seeds;
  for (const int kind : {0, 1, 2, 3}) {  // RadarScan, another schema, PointCloud, PointCloud2
    const bool wrong_schema = kind == 1, cloud = kind == 2, cloud2 = kind == 3;
    std::ostringstream out;
    mcap::Writer writer(out, "ros2");
    const auto scan = cloud    ? writer.add_schema("foxglove.PointCloud", "jsonschema", "{}")
                      : cloud2 ? writer.add_schema("sensor_msgs/msg/PointCloud2", "ros2msg", "")
                               : writer.add_schema(wrong_schema ? "sensor_msgs/msg/Imu" : "radar_msgs/msg/RadarScan", "ros2msg", "");
    const auto odom = writer.add_schema("nav_msgs/msg/Odometry", "ros2msg", "");
    const auto scene = writer.add_schema("foxglove.SceneUpdate", "jsonschema", "{}");
    const auto scan_channel = writer.add_channel("/radar/front/scan", cloud ? "json" : "cdr", scan);
    const auto odom_channel = writer.add_channel("/odom", "cdr", odom);
    const auto scene_channel = writer.add_channel("/annotations", "json", scene);
    const std::int64_t t0_ns = 1'700'000'000'000'000'000;
    for (int k = 0; k < 10; ++k) {
      const std::int64_t t_ns = t0_ns + k * 50'000'000;
      if (k % 2 == 0) {
        writer.write_message(odom_channel, static_cast<std::uint64_t>(t_ns), mcap_seed::odometry(t_ns, 0.05 * k));
        writer.write_message(scene_channel, static_cast<std::uint64_t>(t_ns), mcap_seed::scene_update(t_ns));
      }
      writer.write_message(scan_channel, static_cast<std::uint64_t>(t_ns),
                           cloud    ? mcap_seed::point_cloud(t_ns, 0.05 * k)
                           : cloud2 ? mcap_seed::point_cloud2(t_ns, 0.05 * k)
                                    : mcap_seed::radar_scan(t_ns, 0.05 * k));
    }
    writer.finish();
    const std::string bytes = out.str();
    seeds.emplace_back(cloud ? "point_cloud.mcap" : cloud2 ? "point_cloud2.mcap" : wrong_schema ? "wrong_schema.mcap" : "drive.mcap",
                       std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  }
  return seeds;
}

}  // namespace rcsim::fuzz
