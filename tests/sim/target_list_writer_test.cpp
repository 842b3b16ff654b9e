// Target list output (sim/target_list_writer.hpp): the CSV header per level, one row per target
// in fixed decimals (CSV fields quoted where needed, JSON Lines with the same keys), and the
// ideal level's object and reflector names.
#include "sim/target_list_writer.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "common/angles.hpp"
#include "test_support.hpp"

namespace rcsim::target_list_writer_test {

// A sensor cycle state of the single srr24 of a scene with one passenger car, to fill by hand.
struct Fixture {
  Scene scene = [] {
    Scene s = testing::single_sensor_scene(1.0);
    testing::add_object(s, "car 1", "passenger_car", {testing::sample(0, 15, 0, kPi, 0)});
    return s;
  }();
  SensorModel model{scene.sensors[0], scene.effects, SimulationOptions{}, scene.objects};
  SensorCycleState state{model, 16, scene.cycle_time_s, 0, 0};
};

std::string written(const Fixture& f, TargetListFormat format, ListLevel level, const std::string& sensor_id,
                    long long* rows = nullptr) {
  std::ostringstream out;
  TargetListWriter writer(out, format, level);
  writer.write_header();
  writer.write_sensor_cycle(f.scene, 1, 0.04, sensor_id, f.state);
  if (rows != nullptr) *rows = writer.rows_written();
  return out.str();
}

TEST(TargetListWriter, TracksAndDetectionsInFixedDecimalsByHand) {
  Fixture f;
  f.state.reported = {{7, 12.345678, -0.1234567, -1.5, 20.0004}, {9, 3.0, 0.0, 0.0, -5.0}};
  long long rows = 0;
  // t 6 decimals, range 4, azimuth 6, range rate 4, amplitude 3; a sensor id with a comma quoted.
  EXPECT_EQ(written(f, TargetListFormat::Csv, ListLevel::tracks, "front,left", &rows),
            "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n"
            "0.040000,1,\"front,left\",7,12.3457,-0.123457,-1.5000,20.000\n"
            "0.040000,1,\"front,left\",9,3.0000,0.000000,0.0000,-5.000\n");
  EXPECT_EQ(rows, 2);
  // JSON Lines: no header, the same keys and decimals, the id a JSON string.
  EXPECT_EQ(written(f, TargetListFormat::Jsonl, ListLevel::tracks, "say \"x\""),
            "{\"t_s\":0.040000,\"cycle\":1,\"sensor\":\"say \\\"x\\\"\",\"id\":7,\"range_m\":12.3457,"
            "\"azimuth_rad\":-0.123457,\"range_rate_mps\":-1.5000,\"amplitude_db\":20.000}\n"
            "{\"t_s\":0.040000,\"cycle\":1,\"sensor\":\"say \\\"x\\\"\",\"id\":9,\"range_m\":3.0000,"
            "\"azimuth_rad\":0.000000,\"range_rate_mps\":0.0000,\"amplitude_db\":-5.000}\n");
  // Detections are numbered by their place in the cycle; the tracks are not written at that level.
  Detection d;
  d.range_m = 8.0;
  d.azimuth_rad = 0.25;
  d.range_rate_mps = 2.0;
  d.amplitude_db = 11.1115;
  f.state.detections = {d, d};
  EXPECT_EQ(written(f, TargetListFormat::Csv, ListLevel::detections, "s", &rows),
            "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n"
            "0.040000,1,s,0,8.0000,0.250000,2.0000,11.111\n"
            "0.040000,1,s,1,8.0000,0.250000,2.0000,11.111\n");
  EXPECT_EQ(rows, 2);
}

TEST(TargetListWriter, IdealTargetsNameTheirObjectAndReflector) {
  Fixture f;
  const auto ideal = [](ReflectorKind kind, int reflector, int bounce_order) {
    IdealTarget t;
    t.range_m = 15.0;
    t.object_index = 0;
    t.reflector_index = reflector;
    t.kind = kind;
    t.bounce_order = bounce_order;
    return t;
  };
  // The passenger car's point 0 is corner_front_left, plane 1 the rear; box side 2 is box_left.
  f.state.ideal = {ideal(ReflectorKind::Point, 0, 1), ideal(ReflectorKind::Plane, 1, 2),
                   ideal(ReflectorKind::PlaneDiffuse, 1, 1), ideal(ReflectorKind::BoxDiffuse, 2, 1)};
  f.state.echoes.assign(4, Echo{});
  for (auto& e : f.state.echoes) e.amplitude = 10.0;  // 20 log10(10) = 20 dB
  f.state.echoes[1].amplitude = 0.1;                  // -20 dB
  long long rows = 0;
  EXPECT_EQ(written(f, TargetListFormat::Csv, ListLevel::ideal, "s", &rows),
            "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,object,reflector\n"
            "0.040000,1,s,0,15.0000,0.000000,0.0000,20.000,car 1,corner_front_left\n"
            "0.040000,1,s,1,15.0000,0.000000,0.0000,-20.000,car 1,rear#bounce2\n"
            "0.040000,1,s,2,15.0000,0.000000,0.0000,20.000,car 1,rear#diffuse\n"
            "0.040000,1,s,3,15.0000,0.000000,0.0000,20.000,car 1,box_left#diffuse\n");
  EXPECT_EQ(rows, 4);
  f.state.ideal.resize(1);
  EXPECT_EQ(written(f, TargetListFormat::Jsonl, ListLevel::ideal, "s"),
            "{\"t_s\":0.040000,\"cycle\":1,\"sensor\":\"s\",\"id\":0,\"range_m\":15.0000,\"azimuth_rad\":0.000000,"
            "\"range_rate_mps\":0.0000,\"amplitude_db\":20.000,\"object\":\"car 1\",\"reflector\":\"corner_front_left\"}\n");
}

TEST(TargetListWriter, AnEmptyCycleWritesTheHeaderOnly) {
  Fixture f;
  long long rows = -1;
  EXPECT_EQ(written(f, TargetListFormat::Csv, ListLevel::tracks, "s", &rows),
            "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db\n");
  EXPECT_EQ(rows, 0);
  EXPECT_EQ(written(f, TargetListFormat::Jsonl, ListLevel::detections, "s"), "");
}

}  // namespace rcsim::target_list_writer_test
