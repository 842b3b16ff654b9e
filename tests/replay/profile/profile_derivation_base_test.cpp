// rcsim profile derive (issue 48) on a radar nobody fitted: what it takes from the base, and what
// it must not. A point cloud laid out in code as View-of-Delft's ZF FRGen21 reports it (3 single
// frames, about 300 points each, continuous radial speeds from -25.8 to +18.7 m/s, a few points
// beside the sensor at x = 0), derived with base astyx_hires (Doppler interval +-5.2 m/s):
// - a view field the data push to 90 deg is clamped at the antenna model's limit, said so, and the
//   profile is written (item 1);
// - every value the profile holds that no stage derived is listed as the base's, and a base value
//   the data contradict is replaced, said so (item 2);
// - a cell the pairs do not show (continuous values) is the base's, not "derived" (item 3);
// - every derived number carries an interval, and a value few points show is marked weak (item 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>

#include "common/angles.hpp"
#include "common/json_reader.hpp"
#include "io/recording.hpp"
#include "replay/profile/derivation_checks.hpp"
#include "replay/profile/profile_derivation.hpp"
#include "sensor/sensor_config.hpp"

namespace rcsim::replay::profile {
namespace {

// A seeded uniform draw in [lo, hi): the same numbers on every platform.
class Draws {
 public:
  explicit Draws(std::uint64_t seed) : state_(seed) {}
  double uniform(double lo, double hi) {
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(state_ >> 11) / 9007199254740992.0;
  }

 private:
  std::uint64_t state_;
};

// 3 single frames of 305 points: ranges 2-50 m, azimuths +-60 deg, radial speeds -25.8 to +18.7
// m/s, amplitudes 5 to 35 dB (a relative scale), all continuous; 13 of them (4 + 5 + 4) beside the
// sensor at +-89.9 deg.
Recording point_cloud_frames() {
  Recording r;
  r.dir = "vod_like";
  r.name = "vod_like";
  r.cycle_time_s = 0.1;
  r.timeline = Timeline::snapshots;
  r.ego_motion_known = false;
  RecordingSensor sensor{"radar", "astyx_hires", 0.0, 0.0, 0.0, ListLevel::detections};
  sensor.amplitude_unit = AmplitudeUnit::relative_db;
  r.sensors.push_back(sensor);
  Draws draw(48);
  for (int k = 0; k < 3; ++k) {
    r.ego.push_back({1.0 * k, 0.0, 0.0, 0.0, 0.0, 0.0});
    for (int i = 0; i < 305; ++i) {
      RecordedTarget t;
      t.t_s = 1.0 * k, t.cycle = k;
      t.range_m = draw.uniform(2.0, 50.0);
      t.azimuth_rad = deg_to_rad(i < 4 + k % 2 ? (i % 2 == 0 ? 89.9 : -89.9) : draw.uniform(-60.0, 60.0));
      t.range_rate_mps = draw.uniform(-25.8, 18.7);
      t.amplitude_db = draw.uniform(5.0, 35.0);
      r.targets.push_back(t);
    }
  }
  r.targets.front().range_rate_mps = -25.8, r.targets.back().range_rate_mps = 18.7;
  return r;
}

ProfileDerivation derived_from_point_cloud() {
  static const Recording frames = point_cloud_frames();
  return derive_profile({&frames}, {.base = "astyx_hires", .name = "vod_like"});
}

TEST(ProfileDeriveBase, AViewFieldAtNinetyDegreesIsClampedAtTheAntennaModelsLimitAndWritten) {
  // The 0.1 % and 99.9 % quantiles of 915 azimuths lie among the 13 points at +-89.9 deg: 90 deg
  // to 0.5 deg, which the antenna model (the front half) cannot hold. Clamped to 89.5, said so.
  const ProfileDerivation d = derived_from_point_cloud();
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  const DerivedValue& half = values.at("field_of_view.azimuth_half_deg");
  EXPECT_EQ(half.source, ValueSource::derived);
  EXPECT_DOUBLE_EQ(half.value.get<double>(), 89.5) << half.evidence;
  EXPECT_NE(half.evidence.find("clamped from 90.0 to 89.5 deg, the antenna model's limit"), std::string::npos) << half.evidence;
  EXPECT_NE(half.evidence.find("13 detection(s)"), std::string::npos) << half.evidence;
  // Fewer than 1000 points: the quantiles rest on less than one point beyond them.
  EXPECT_TRUE(half.weak) << half.evidence;
  // What is written is a profile replay reads.
  const SensorConfig config = parse_sensor_config(JsonField(d.profile, "vod_like", ""));
  EXPECT_NEAR(rad_to_deg(config.fov.azimuth_half_rad), 89.5, 1e-9);
}

// Issue 48, item 3: the same frames with the radar's RCS as the amplitude (-60 to -30 dB): the
// derived threshold lies far below the base's noise at 0 dB, so the floor moves with it, keeping
// astyx_hires's 45 dB of threshold above noise, and the profile is written and reads back.
TEST(ProfileDeriveBase, ARelativeScaleBelowZeroGetsItsNoiseFloorBelowItsThreshold) {
  Recording frames = point_cloud_frames();
  for (RecordedTarget& t : frames.targets) t.amplitude_db -= 65.0;
  const ProfileDerivation d = derive_profile({&frames}, {.base = "astyx_hires", .name = "rcs_radar"});
  const double threshold_db = d.profile["amplitude"]["detection_threshold_db"].get<double>();
  EXPECT_LT(threshold_db, -55.0);
  ASSERT_TRUE(d.profile["amplitude"].contains("noise_floor_db"));
  EXPECT_NEAR(d.profile["amplitude"]["noise_floor_db"].get<double>(), threshold_db - 45.0, 0.05);
  const SensorConfig config = parse_sensor_config(JsonField(nlohmann::json::parse(d.profile.dump()), "rcs_radar.json", ""));
  EXPECT_LT(config.amplitude.noise_floor_db, config.amplitude.detection_threshold_db);
  const auto row = std::find_if(d.values.begin(), d.values.end(), [](const DerivedValue& v) { return v.field == "amplitude.noise_floor_db"; });
  ASSERT_NE(row, d.values.end());
  EXPECT_EQ(row->source, ValueSource::base);
  EXPECT_NE(row->evidence.find("45.0 dB above its noise"), std::string::npos) << row->evidence;
  // The law's level, the base's 73 dB on the Mag scale, moved with the threshold (45 -> its value).
  EXPECT_NEAR(d.profile["amplitude"]["snr_at_1m_for_1m2_db"].get<double>(), 73.0 + (threshold_db - 45.0), 0.05);
  // On the base's own scale (a threshold of 45, as astyx_hires's) the floor stays at 0: nothing written.
  Recording on_base_scale = point_cloud_frames();
  for (RecordedTarget& t : on_base_scale.targets) t.amplitude_db += 40.0;
  const ProfileDerivation same = derive_profile({&on_base_scale}, {.base = "astyx_hires", .name = "same"});
  EXPECT_EQ(same.profile["amplitude"]["detection_threshold_db"].get<double>(), 45.0);
  EXPECT_FALSE(same.profile["amplitude"].contains("noise_floor_db"));
}

TEST(ProfileDeriveBase, ABaseDopplerIntervalTheSpeedsRunBeyondIsDroppedSaidSo) {
  const ProfileDerivation d = derived_from_point_cloud();
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  // astyx_hires's [-5.2374, 5.1562] m/s: the radial speeds run from -25.8 to +18.7 m/s.
  const DerivedValue& interval = values.at("resolution.unambiguous_range_rate_mps");
  EXPECT_EQ(interval.source, ValueSource::derived);
  EXPECT_TRUE(interval.value.is_null());
  EXPECT_EQ(value_text(interval.value), "none");
  EXPECT_NE(interval.evidence.find("dropped (no Doppler aliasing): the recordings' radial speeds run from -25.80 to 18.70 m/s"),
            std::string::npos)
      << interval.evidence;
  EXPECT_FALSE(d.profile.at("resolution").contains("unambiguous_range_rate_mps"));
  EXPECT_FALSE(parse_sensor_config(JsonField(d.profile, "vod_like", "")).resolution.aliases_range_rate());
}

TEST(ProfileDeriveBase, EveryValueTheProfileTakesFromTheBaseIsListedAsTheBases) {
  const ProfileDerivation d = derived_from_point_cloud();
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  // Every number, word or list of the written profile is a listed value (the background is its own).
  std::vector<std::string> unlisted;
  const auto walk = [&](const auto& self, const nlohmann::ordered_json& node, const std::string& prefix) -> void {
    for (const auto& [key, child] : node.items()) {
      const std::string field = prefix.empty() ? key : prefix + "." + key;
      if (prefix.empty() && (key == "format" || key == "version" || key == "name" || key == "description" || key == "background")) continue;
      if (child.is_object()) {
        self(self, child, field);
      } else if (!values.contains(field)) {
        unlisted.push_back(field);
      }
    }
  };
  walk(walk, d.profile, "");
  EXPECT_TRUE(unlisted.empty()) << unlisted.front();
  // What no stage reads is the base's, with the base's value, and the description names it.
  for (const char* field : {"occlusion.loss_db", "extended_objects.max_pieces_per_face", "detection.reported_beams", "array.pointer_noise_sigma",
                            "multibounce.max_range_m", "carrier_frequency_hz", "cycle_time_s"}) {
    ASSERT_TRUE(values.contains(field)) << field;
    EXPECT_EQ(values.at(field).source, ValueSource::base) << field;
    EXPECT_EQ(values.at(field).value.dump(), d.profile.at(field_pointer(field)).dump()) << field;
    EXPECT_NE(d.profile.at("description").get<std::string>().find(field), std::string::npos) << field;
  }
}

TEST(ProfileDeriveBase, ABaseMinimumRangeBeyondTheNearestDetectionIsReplaced) {
  // A base whose minimum range (20 m) lies beyond the nearest detection (10 m), which lies too far
  // out (over 5 % of the farthest) for the stage to read the radar's own: the base is contradicted.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rcsim_profile_base_test";
  std::filesystem::create_directories(dir);
  nlohmann::ordered_json base = nlohmann::ordered_json::parse(builtin_sensor_text("aimotive_lrr"));
  base["field_of_view"]["min_range_m"] = 20.0;
  const std::filesystem::path base_file = dir / "far_min_range.json";
  std::ofstream(base_file) << base.dump(2);
  Recording r = point_cloud_frames();
  r.timeline = Timeline::drive;
  for (RecordedTarget& t : r.targets) t.range_m = 10.0 + 4.0 * (t.range_m - 2.0), t.azimuth_rad = std::clamp(t.azimuth_rad, -0.2, 0.2);
  const ProfileDerivation d = derive_profile({&r}, {.base = base_file.string(), .name = "far"});
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  const DerivedValue& min_range = values.at("field_of_view.min_range_m");
  EXPECT_EQ(min_range.source, ValueSource::derived);
  EXPECT_LT(min_range.value.get<double>(), 20.0);
  EXPECT_NE(min_range.evidence.find("the base's 20.00 m replaced: the nearest detection lies at"), std::string::npos) << min_range.evidence;
  EXPECT_DOUBLE_EQ(d.profile.at("field_of_view").at("min_range_m").get<double>(), min_range.value.get<double>());
  std::filesystem::remove_all(dir);
}

TEST(ProfileDeriveBase, ACellThePairsDoNotShowIsTheBasesNotDerived) {
  // Continuous ranges and radial speeds: the pairs' distances spread smoothly from zero, so the
  // 1 % quantile (a thousandth of a m/s) is no cell. It is the base's, saying why.
  const ProfileDerivation d = derived_from_point_cloud();
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  for (const char* field : {"resolution.range_cell_m", "resolution.range_rate_cell_mps"}) {
    const DerivedValue& cell = values.at(field);
    EXPECT_EQ(cell.source, ValueSource::base) << field << ": " << cell.evidence;
    EXPECT_EQ(cell.value.dump(), d.profile.at(field_pointer(field)).dump()) << field;
  }
  EXPECT_DOUBLE_EQ(values.at("resolution.range_rate_cell_mps").value.get<double>(), 0.0812);
  EXPECT_NE(values.at("resolution.range_cell_m").evidence.find("not shown by the pairs"), std::string::npos)
      << values.at("resolution.range_cell_m").evidence;
}

TEST(ProfileDeriveBase, EveryDerivedNumberCarriesAnIntervalAroundIt) {
  const ProfileDerivation d = derived_from_point_cloud();
  for (const DerivedValue& v : d.values) {
    if (v.source != ValueSource::derived || !v.value.is_number()) continue;
    ASSERT_TRUE(v.has_interval()) << v.field << ": " << v.evidence;
    EXPECT_LE(v.low, v.value.get<double>() + 1e-9) << v.field;
    EXPECT_GE(v.high, v.value.get<double>() - 1e-9) << v.field;
  }
  // 915 points: the quantile readings are weak, and say so in the source column.
  const std::map<std::string, DerivedValue> values = testing::by_field(d.values);
  const DerivedValue& threshold = values.at("amplitude.detection_threshold_db");
  EXPECT_TRUE(threshold.weak);
  EXPECT_EQ(source_text(threshold), "derived, weak");
  EXPECT_NE(interval_text(threshold), "");
}

}  // namespace
}  // namespace rcsim::replay::profile
