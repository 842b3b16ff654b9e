#pragma once
// Fuzz entry point of the ASAM OpenLABEL reader (`rcsim import --from mcap` with the mapping's
// objects.openlabel, replay/import/openlabel.hpp, docs/fuzzing.md). The input is an OpenLABEL JSON
// file; what the reader accepts must hold what it promises: every box finite, its size positive,
// its yaw within [-pi, pi], its object among the file's. Seeds: written by the harness itself, a
// file with quaternion and Euler cuboids, static object data, number and string timestamps, an
// ISO 8601 one and speeds.
#include <cmath>
#include <set>

#include "common/angles.hpp"
#include "fuzz/fuzz_support.hpp"
#include "replay/import/openlabel.hpp"

namespace rcsim::fuzz {

inline void fuzz_openlabel(Input data) {
  const std::filesystem::path dir = fresh_dir("openlabel");
  write_file(dir / "labels.json", as_text(data));
  refusals_are_fine([&] {
    const replay::openlabel::Labels labels = replay::openlabel::read_openlabel(dir / "labels.json");
    for (const replay::openlabel::LabelledBox& b : labels.boxes) {
      for (const double v : {b.x_m, b.y_m, b.z_m, b.yaw_rad, b.length_m, b.width_m, b.height_m}) {
        if (!std::isfinite(v)) throw Finding("read_openlabel accepted a box with a value that is not finite: object " + b.uid);
      }
      if (!(b.length_m > 0.0 && b.width_m > 0.0 && b.height_m > 0.0)) throw Finding("read_openlabel accepted a box of no size: " + b.uid);
      if (std::abs(b.yaw_rad) > kPi + 1e-12) throw Finding("read_openlabel gave a yaw beyond [-pi, pi]: " + b.uid);
      if (b.speed_mps && !std::isfinite(*b.speed_mps)) throw Finding("read_openlabel accepted a speed that is not finite: " + b.uid);
      if (b.type.empty()) throw Finding("read_openlabel gave a box of an object without a type: " + b.uid);
    }
  });
}

inline std::vector<std::pair<std::string, std::vector<std::uint8_t>>> openlabel_seeds() {
  const std::string labels = R"({"openlabel": {"metadata": {"schema_version": "1.0.0"},
  "objects": {"car1": {"name": "car1", "type": "Car"},
              "truck": {"name": "truck", "type": "Truck", "coordinate_system": "base_link",
                        "object_data": {"cuboid": [{"name": "box", "val": [10.0, 3.5, 1.5, 0.0, 0.0, 0.1, 0.0, 12.0, 2.5, 3.5]}],
                                        "num": [{"name": "speed_mps", "val": 20.5}]}}},
  "coordinate_systems": {"odom": {"type": "scene_cs", "parent": "", "children": ["base_link"]},
                         "base_link": {"type": "local_cs", "parent": "odom", "children": []}},
  "frames": {
    "0": {"frame_properties": {"timestamp": 1700000000.05},
          "objects": {"car1": {"object_data": {"cuboid": [{"name": "box", "coordinate_system": "odom",
                                                          "val": [20.0, -1.0, 0.75, 0.0, 0.0, 0.2474, 0.9689, 4.6, 1.8, 1.5]}],
                                               "num": [{"name": "speed", "val": 13.9}]}},
                      "truck": {}}},
    "1": {"frame_properties": {"timestamp": "1700000000.150000001"},
          "objects": {"car1": {"object_data": {"cuboid": [{"name": "box", "val": [21.4, -1.0, 0.75, 0.0, 0.0, 0.5, 4.6, 1.8, 1.5]}]}}}},
    "2": {"frame_properties": {"timestamp": "2023-11-14T22:13:20.250Z"},
          "objects": {"car1": {"object_data": {"cuboid": [{"name": "box", "val": null}]}}, "truck": {}}}
  },
  "frame_intervals": [{"frame_start": 0, "frame_end": 2}]}})";
  return {{"labels", std::vector<std::uint8_t>(labels.begin(), labels.end())}};
}

}  // namespace rcsim::fuzz
