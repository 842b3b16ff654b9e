#pragma once
// The stated bounds of what rcsim reads (schemas/limits.md). Beyond them a value is a unit or
// format error (metres given in millimetres, an angle in degrees, a corrupted file), not a
// measurement or a configuration, and it is refused naming the file, line or field: a range of
// 1e308 must never be averaged into GOSPA, nor a track table of INT_MAX entries allocated.
#include <cstdint>

namespace rcsim::limits {

inline constexpr double kMaxCoordinate_m = 1e7;     // a position in a world frame: 10,000 km
inline constexpr double kMaxTime_s = 1e7;           // a time or duration: 115 days
inline constexpr double kMaxCycleTime_s = 10.0;     // a sensor cycle
inline constexpr double kMaxSize_m = 100.0;         // an object's or model's length, width, offsets
inline constexpr double kMaxMountOffset_m = 100.0;  // a sensor's position in the vehicle frame
inline constexpr double kMaxSpeed_mps = 1000.0;            // a speed or a target's range rate
inline constexpr double kMaxYawRate_radps = 100.0;
inline constexpr double kMaxErcs = 1e4;              // equivalent reflection cross-section (paper eq. 1)
inline constexpr double kMaxRange_m = 10'000.0;      // a sensor's range, a target's range
inline constexpr double kMaxAzimuth_rad = 3.15;      // a target's azimuth, ±π: beyond, degrees?
inline constexpr double kMaxLevel_dB = 1000.0;       // an amplitude, threshold, SNR or RCS in dB
inline constexpr double kMaxUnwrappedYaw_rad = 1e6;  // an unwrapped heading (laps of a ring road)
inline constexpr double kMaxYaw_rad = 6.2832;        // a wrapped heading, ±2π: beyond, degrees?
inline constexpr double kMaxMountYaw_rad = 3.1416;   // a mounting angle, ±π: beyond, degrees?
inline constexpr double kMaxMountPitch_rad = 0.7854; // a mounting's pitch, ±π/4: a radar looks along the road
inline constexpr int kMaxCount = 1'000'000;          // a count in a configuration (tracks, hits)
inline constexpr int kMaxTracks = 100'000;           // a sensor's track table
// An imported scan's returns (a RadarScan's, a point cloud's points): the densest imaging radars
// report some 10^4 a scan; 2^18 leave a margin and cost 5 MiB as 20-byte returns.
inline constexpr std::uint32_t kMaxReturnsPerScan = 262'144;

}  // namespace rcsim::limits
