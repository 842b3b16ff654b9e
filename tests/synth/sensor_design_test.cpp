// One radar per sensor profile (docs/synth.md, "One radar per profile"): srr24 is the reference
// design itself; aimotive_lrr becomes a 77 GHz long-range radar whose figures follow from its
// profile by the FMCW relations; what cannot be synthesised, or cannot share one recording, is
// refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sensor/sensor_config.hpp"
#include "synth/propagation.hpp"
#include "synth/reference_simulator.hpp"
#include "synth/sensor_design.hpp"
#include "synth/signal_chain.hpp"
#include "test_support.hpp"

namespace rcsim::synth {
namespace {

// The message of the std::invalid_argument that f throws (empty when it throws none).
template <typename F>
std::string design_refusal(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SynthSensorDesign, Srr24IsTheReferenceDesignBitForBit) {
  // The design's figures are srr24's: the derivation must give them back exactly, or every
  // bundled recording's synthesis (tests/golden) would change.
  const SynthConfig design;
  EXPECT_TRUE(sensor_design(builtin_sensor_config("srr24"), design) == design);
}

TEST(SynthSensorDesign, AimotiveLrrIsA77GhzLongRangeRadar) {
  const SynthConfig design;
  const SensorConfig profile = builtin_sensor_config("aimotive_lrr");
  const SynthConfig lrr = sensor_design(profile, design);
  const Derived d = derive(lrr);
  EXPECT_EQ(lrr.waveform.carrier_hz, 77.0e9);
  EXPECT_NEAR(d.range_bin_m, 1.4, 0.01);           // c / 2B from the profile's 1.4 m cell (B = 107 MHz)
  EXPECT_NEAR(d.range_rate_bin_mps, 0.2, 0.002);   // lambda / (2 N_c T_c) from its 0.2 m/s cell
  EXPECT_GE(d.range_rate_bin_mps * lrr.waveform.chirps / 2.0, 32.0);  // +-51 m/s unambiguous
  EXPECT_LE(d.frame_s, profile.cycle_time_s);
  EXPECT_EQ(lrr.antenna.max_range_m, 180.0);
  EXPECT_NEAR(lrr.antenna.azimuth_half_fov_deg, 17.0, 1e-9);
  EXPECT_EQ(lrr.antenna.element_spacing_wavelengths, 1.5);
  // Beyond the 1.5-wavelength pair's first grating angle nothing is illuminated that would fold
  // into the field of view: sin(phi) < 1/1.5 - sin(17 deg).
  EXPECT_NEAR(lrr.antenna.azimuth_half_illuminated_deg, rad_to_deg(std::asin(1.0 / 1.5 - std::sin(deg_to_rad(17.0)))), 1e-6);
  // Nothing synthesised folds back: N_s range bins cover the synthesis range, which covers 180 m.
  EXPECT_GE(lrr.if_filter.synthesis_max_range_m, 180.0);
  EXPECT_GE(lrr.waveform.samples_per_chirp * d.range_bin_m, lrr.if_filter.synthesis_max_range_m);
  EXPECT_TRUE(lrr.reports_detections);
  // The link budget: a car-sized unit scatterer at 180 m has the SNR the design gives it at 40 m.
  EXPECT_NEAR(unit_scatterer_snr_db(lrr, 180.0), unit_scatterer_snr_db(design, 40.0), 1e-9);
  // Its amplitude is an SNR (the profile's law is the radar equation): noise reads about 0 dB.
  const SignalChain chain(lrr);
  EXPECT_NEAR(chain.noise_floor_db(), 0.0, 1.0);
}

TEST(SynthSensorDesign, LrrChainFindsAPointAt120Metres) {
  SynthConfig lrr = sensor_design(builtin_sensor_config("aimotive_lrr"), SynthConfig{});
  lrr.propagation.ground_reflection = 0.0;
  SignalChain chain(lrr);
  const Propagator p(lrr);
  // A unit point scatterer (a car's worth) at 120 m, 5 deg off boresight, receding at 3 m/s.
  const double range_m = 120.0, azimuth_rad = deg_to_rad(5.0);
  const double a = (10.0 / range_m) * (10.0 / range_m) * p.if_gain(range_m);
  const auto [sum, delta] = p.antenna(azimuth_rad, 0.0);
  Rng rng(5);
  const auto detections = chain.process({{range_m, 3.0, azimuth_rad, a * sum, a * delta}}, rng);
  // Besides it, receiver noise gives about one false alarm per frame (the design's count).
  const auto near = std::find_if(detections.begin(), detections.end(), [](const Detection& d) { return std::abs(d.range_m - 120.0) < 3.0; });
  ASSERT_NE(near, detections.end());
  EXPECT_NEAR(near->range_m, 120.0, 0.5);
  EXPECT_NEAR(near->range_rate_mps, 3.0, 0.1);
  EXPECT_NEAR(near->azimuth_rad, azimuth_rad, deg_to_rad(0.5));
  EXPECT_GT(near->snr_db, 15.0);
  EXPECT_LE(detections.size(), 4u);
}

TEST(SynthSensorDesign, LrrFalseAlarmsPerFrameAsTheDesigns) {
  // Four times the design's cells, a quarter of its false-alarm probability per cell: receiver
  // noise alone gives about as many false detections per frame.
  const SynthConfig design;
  SignalChain srr(design);
  SignalChain lrr(sensor_design(builtin_sensor_config("aimotive_lrr"), design));
  Rng rng(17);
  const int frames = 40;
  double srr_alarms = 0.0, lrr_alarms = 0.0;
  for (int i = 0; i < frames; ++i) {
    srr_alarms += static_cast<double>(srr.process({}, rng).size()) / frames;
    lrr_alarms += static_cast<double>(lrr.process({}, rng).size()) / frames;
  }
  EXPECT_GT(srr_alarms, 0.1);
  EXPECT_GT(lrr_alarms, 0.5 * srr_alarms);
  EXPECT_LT(lrr_alarms, 2.0 * srr_alarms);
}

TEST(SynthSensorDesign, RefusesAProfileItCannotSynthesiseByName) {
  SensorConfig fast = builtin_sensor_config("srr24");
  fast.name = "fast_srr";
  fast.cycle_time_s = 0.005;  // the 12.5 ms frame does not fit
  const std::string frame = design_refusal([&] { sensor_design(fast, SynthConfig{}); });
  EXPECT_NE(frame.find("\"fast_srr\""), std::string::npos) << frame;
  EXPECT_NE(frame.find("cycle time of 0.005 s"), std::string::npos) << frame;

  SensorConfig fine = builtin_sensor_config("srr24");
  fine.name = "fine_doppler";
  fine.resolution.range_rate_cell_mps = 0.001;  // 64,000 chirps for +-32 m/s
  const std::string chirps = design_refusal([&] { sensor_design(fine, SynthConfig{}); });
  EXPECT_NE(chirps.find("\"fine_doppler\""), std::string::npos) << chirps;
  EXPECT_NE(chirps.find("4096 chirps"), std::string::npos) << chirps;

  // Through a scene: the sensor's id comes first.
  Scene scene = testing::single_sensor_scene(1.0);
  scene.sensors[0].config = fast;
  const std::string named = design_refusal([&] { sensor_designs(scene, SynthConfig{}); });
  EXPECT_EQ(named.rfind("sensor \"" + scene.sensors[0].id + "\": sensor profile \"fast_srr\"", 0), 0u) << named;
}

TEST(SynthSensorDesign, OneRecordingHasOneCycleClockAndOneLevel) {
  Scene scene = testing::single_sensor_scene(1.0);
  EXPECT_EQ(design_refusal([&] { require_one_recording(scene, SynthConfig{}); }), "");
  // srr24 (0.04 s) and aimotive_lrr (0.0554 s): refused naming both and their cycle times.
  MountedSensor lrr = scene.sensors[0];
  lrr.id = "lrr_front";
  lrr.config = builtin_sensor_config("aimotive_lrr");
  scene.sensors.push_back(lrr);
  const std::string mixed = design_refusal([&] { require_one_recording(scene, SynthConfig{}); });
  EXPECT_NE(mixed.find("\"" + scene.sensors[0].id + "\" (srr24) 0.04 s"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("\"lrr_front\" (aimotive_lrr) 0.0554 s"), std::string::npos) << mixed;
  EXPECT_THROW(make_recording(scene, SynthConfig{}, 1, {"mixed", "", "test"}), std::invalid_argument);
  // One sensor alone, but the scene asks for another cycle time than its own.
  scene.sensors.pop_back();
  scene.cycle_time_s = 0.05;
  const std::string other = design_refusal([&] { require_one_recording(scene, SynthConfig{}); });
  EXPECT_NE(other.find("not the scene's 0.05 s: \"s\" (srr24) 0.04 s"), std::string::npos) << other;
  // Tracks and raw detections at one cycle time: targets.csv cannot hold both.
  scene.cycle_time_s = 0.04;
  MountedSensor detecting = scene.sensors[0];
  detecting.id = "detecting";
  detecting.config.reports = ListLevel::detections;
  scene.sensors.push_back(detecting);
  const std::string levels = design_refusal([&] { require_one_recording(scene, SynthConfig{}); });
  EXPECT_NE(levels.find("\"detecting\" (srr24) raw detections"), std::string::npos) << levels;
}

}  // namespace
}  // namespace rcsim::synth
