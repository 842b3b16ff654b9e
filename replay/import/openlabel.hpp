#pragma once
// Annotated 3D boxes from an ASAM OpenLABEL 1.0 JSON file (ASAM OpenLABEL V1.0.0, 2021-11-09,
// chapter 7; its openlabel_json_schema.json), read with simdjson's on-demand API: an hour of labels
// can be hundreds of megabytes of JSON (read_text_file's limit, 256 MiB, holds).
//
// What is read:
// - openlabel.metadata.schema_version (required by the standard; any value is taken);
// - openlabel.objects.UID: "type" (required), "coordinate_system", and object_data "cuboid" and
//   "num" given there, which are static: they hold in every frame that lists the object;
// - openlabel.frames.N (N digits; boxes come out in increasing N whatever the file's order):
//   frame_properties.timestamp, and objects.UID.object_data "cuboid" and "num". A frame's own
//   cuboids of an object replace the object's static ones in that frame.
// - A cuboid's val: 10 numbers (x, y, z, qx, qy, qz, qw, sx, sy, sz), the quaternion in SciPy's
//   scalar-last order and possibly not of unit norm, or 9 (x, y, z, rx, ry, rz, sx, sy, sz), Euler
//   angles applied in ZYX order, so rz is the yaw. Every cuboid of an object in a frame is one box;
//   a null val (the schema allows it) is none. Its coordinate_system, else its object's, else "".
// - speed_mps: a "num" named "speed_mps", else one named "speed" (taken as m/s), whose "type" is
//   absent or "value": from the cuboid's attributes, else the frame's object_data, else the
//   object's static object_data.
// - The timestamp: seconds since the epoch as a JSON number or a string holding a decimal number
//   ("1700000000.123456789", "1.7e9"), converted from its decimal digits (not through a double) and
//   rounded to the nearest ns; or a string holding an ISO 8601 time with its zone,
//   YYYY-MM-DD(T| )hh:mm:ss[.fraction](Z|±hh:mm|±hhmm|±hh), no leap second. A time without a zone
//   (the standard's own example "2020-04-11 12:00:01") is refused: it names no instant. A frame
//   with no box needs no timestamp.
//
// Not read: frame_intervals, object_data_pointers, coordinate_systems and transforms (boxes stay
// in the frame they name), streams and sync, ontologies, actions, events, contexts, relations,
// and every other object_data type (bbox, poly3d, vec, text, boolean, ...).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rcsim::replay::openlabel {

// The boxes a file may give (schemas/limits.md): a frame listing an object by its uid alone
// ("7": {}, 7 bytes) copies the object's static cuboids into it, so boxes are bounded by the bytes
// behind them, one per kFileBytesPerBox bytes of the file, and at most kMaxBoxesPerFrame a frame
// (a busy scene labels some hundreds of objects). Checked before a box is copied.
inline constexpr std::size_t kFileBytesPerBox = 4;
inline constexpr std::size_t kMaxBoxesPerFrame = 10'000;

// One labelled cuboid of one object in one frame.
struct LabelledBox {
  std::string uid;                // the object's key in openlabel.objects
  std::string type;               // the object's "type" (e.g. "Car"), the class rcsim maps to an object model
  std::int64_t t_ns = 0;          // the frame's time, ns since the epoch
  std::string coordinate_system;  // the cuboid's (else its object's) "coordinate_system", or ""
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;  // the centre
  double yaw_rad = 0.0;                    // heading about z, in [-pi, pi]
  double length_m = 0.0, width_m = 0.0, height_m = 0.0;  // sx, sy, sz
  std::optional<double> speed_mps;
};

struct Labels {
  std::string schema_version;
  std::vector<LabelledBox> boxes;  // in frame order, then object and cuboid order as in the file
};

// Throws rcsim::InputError naming the file and the JSON path of the offending field (e.g.
// "openlabel.frames.12.objects.3.object_data.cuboid[0].val") for: not JSON, not OpenLABEL (no
// "openlabel" in the root object), no schema_version, an object without a type, a frame key that is
// no number, a cuboid val of other than 9 or 10 numbers, a number that is not finite, a size <= 0, a
// quaternion of zero norm, a frame object whose uid is not among openlabel.objects, a frame with
// boxes and without a usable timestamp, more boxes than the bounds above.
Labels read_openlabel(const std::filesystem::path& file);

}  // namespace rcsim::replay::openlabel
