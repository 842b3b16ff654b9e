#pragma once
// The typed result of each stage of the sensor cycle (STYLE.md):
// IdealTargets -> Echoes -> ResolutionCells -> Detections -> (tracker) -> ReportedTargets.
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "common/pose2.hpp"

namespace rcsim {

// Plane: a plane reflector's specular reflection point (paper II-A, Fig. 7); PlaneDiffuse: one
// range cell's piece of its face (the diffuse return a fine-resolution radar resolves); BoxDiffuse:
// the same on a side of the object's box (extended_objects.diffuse_surface "box").
enum class ReflectorKind : std::uint8_t { Point, Plane, PlaneDiffuse, BoxDiffuse };

// One entry of the ideal target list: a visible reflection center (paper IV-3).
struct IdealTarget {
  Vec2 p_WT_W = Vec2::Zero();  // reflection point in the world
  double range_m = 0.0;
  double azimuth_rad = 0.0;
  // sin and cos of azimuth_rad, from the line of sight (the antenna pattern, eq. (6), reads them).
  double sin_azimuth = 0.0;
  double cos_azimuth = 1.0;
  double range_rate_mps = 0.0;
  double ercs = 0.0;
  int object_index = -1;
  int reflector_index = -1;  // into the model's points (Point), planes (Plane, PlaneDiffuse) or box_sides (BoxDiffuse)
  ReflectorKind kind = ReflectorKind::Point;
  int bounce_order = 1;  // 1 direct; k > 1 a back-and-forth duplicate at k times the range

  // Sets azimuth_rad with its sine and cosine.
  void set_azimuth(double angle_rad) {
    azimuth_rad = angle_rad;
    sin_azimuth = std::sin(angle_rad);
    cos_azimuth = std::cos(angle_rad);
  }

  double z_WT_m = 0.0;         // its height above the road (a radar that measures elevation)
  double elevation_rad = 0.0;  // 0 for a planar radar
  // A limb's or a wheel's swing (micro-Doppler, object_model.hpp Swing): its speed along the
  // object's heading on top of the body's motion at this cycle's time.
  double swing_mps = 0.0;
};
using IdealTargets = std::vector<IdealTarget>;

// A reflector's echo: amplitude and the weighted sum/delta pointers (eqs. (3), (6), (8)).
struct Echo {
  double range_m = 0.0;
  double range_rate_mps = 0.0;
  double azimuth_rad = 0.0;
  double amplitude = 0.0;  // A_n, linear, eq. (3)
  std::complex<double> sum_pointer;
  std::complex<double> delta_pointer;
  int ideal_index = -1;
  double elevation_rad = 0.0;
};
using Echoes = std::vector<Echo>;

// One range/range-rate resolution cell (paper III-C).
struct ResolutionCellSum {
  double range_m = 0.0;          // eq. (4)
  double range_rate_mps = 0.0;   // eq. (4)
  double azimuth_rad = 0.0;      // eq. (4) applied to the azimuth: the beam's angle (imaging arrays)
  double amplitude_upper = 0.0;  // A_cell^u: sum of member amplitudes
  std::complex<double> sum_pointer;
  std::complex<double> delta_pointer;
  int strongest_ideal_index = -1;
  int member_count = 0;
  double elevation_rad = 0.0;    // eq. (4) applied to the elevation (a radar that measures it)
};
using ResolutionCells = std::vector<ResolutionCellSum>;

// A measured target before tracking.
struct Detection {
  double range_m = 0.0;
  double azimuth_rad = 0.0;
  double range_rate_mps = 0.0;
  double amplitude_db = 0.0;
  int object_index = -1;  // truth of the strongest member; -1 for clutter
  double elevation_rad = 0.0;  // 0 for a planar radar
};
using Detections = std::vector<Detection>;

// A target in the sensor's final (tracked) target list.
struct ReportedTarget {
  int id = 0;
  double range_m = 0.0;
  double azimuth_rad = 0.0;
  double range_rate_mps = 0.0;
  double amplitude_db = 0.0;
  double elevation_rad = 0.0;  // 0 for a planar radar
};
using ReportedTargets = std::vector<ReportedTarget>;

}  // namespace rcsim
