// A recording read row by row (io/recording_stream.hpp): the header pass (cycle count, checksum),
// each file's row reader on its own, and targets asked for cycle by cycle, in order.
#include "io/recording_stream.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "refusal.hpp"
#include "scratch_dir.hpp"

namespace rcsim::recording_stream_test {

namespace fs = std::filesystem;

using testing::refusal_of;

class RecordingStreamFiles : public testing::ScratchDirTest {
 protected:
  RecordingStreamFiles() : ScratchDirTest("recording_stream") {
    rec_.name = "stream";
    rec_.cycle_time_s = 0.04;
    rec_.sensors = {{"front", "srr24", 3.7, 0.0, 0.0}};
    rec_.objects = {{"car1", "passenger_car", 4.5, 1.8}};
    rec_.boxes.resize(1);
    for (int k = 0; k < 3; ++k) {
      rec_.ego.push_back({0.04 * k, 2.0 * k, 0.0, 0.0, 50.0, 0.0});
      rec_.boxes[0].push_back({0.04 * k, 20.0 + k, 1.0, 0.0, 0.0, 0});
    }
    // Cycle 0: two targets; cycle 1: none; cycle 2: one.
    rec_.targets = {{0.0, 0, 0, 1, 15.0, 0.1, -2.0, 12.5}, {0.0, 0, 0, 2, 16.0, -0.1, -2.0, 11.0},
                    {0.08, 2, 0, 1, 17.0, 0.1, -2.0, 12.0}};
  }
  fs::path written() {
    const fs::path dir = dir_ / "rec";
    write_recording(dir, rec_);
    return dir;
  }
  Recording rec_;
};

TEST_F(RecordingStreamFiles, TheHeaderPassCountsCyclesAndHashesTheFourFiles) {
  const fs::path dir = written();
  RecordingStream stream(dir);
  EXPECT_EQ(stream.header().name, "stream");
  EXPECT_TRUE(stream.header().ego.empty());  // no rows in the header
  EXPECT_EQ(stream.header().streamed_cycles, 3);
  EXPECT_EQ(stream.header().cycle_count(), 3);
  EXPECT_EQ(stream.boxes_path(), (dir / "objects.csv").string());
  // FNV-1a 64 of the four files one after the other, chained from the hash of "rcsim-recording/1".
  const std::string all = testing::file_bytes(dir / "recording.json") + testing::file_bytes(dir / "ego.csv") + testing::file_bytes(dir / "objects.csv") +
                          testing::file_bytes(dir / "targets.csv");
  EXPECT_EQ(recording_checksum(dir), fnv1a64(all, fnv1a64("rcsim-recording/1")));
  EXPECT_EQ(stream.header().checksum, recording_checksum(dir));
  EXPECT_EQ(read_recording(dir).checksum, recording_checksum(dir));
  // recording.json alone: no checksum, no cycles.
  const Recording header = read_recording_header(dir);
  EXPECT_EQ(header.sensors.size(), 1u);
  EXPECT_EQ(header.checksum, 0u);
  EXPECT_EQ(header.cycle_count(), 0);
  EXPECT_EQ(refusal_of([&] { read_recording_header(dir / "ego.csv"); }),
            (dir / "ego.csv").string() + ": not a recording directory");
  // Blank lines are no cycles.
  std::ofstream(dir / "ego.csv", std::ios::app) << "\n \n";
  EXPECT_EQ(RecordingStream(dir).header().streamed_cycles, 3);
}

// A file cut inside its last number still has the header's fields ("...,17.0,-2.0,1" for
// 12.0): without the line end every writer puts there, it is refused as cut short, not read.
TEST_F(RecordingStreamFiles, ACsvWhoseLastLineHasNoLineEndIsRefusedAsCutShort) {
  const fs::path dir = written();
  std::string targets = testing::file_bytes(dir / "targets.csv");
  ASSERT_EQ(targets.back(), '\n');
  targets.resize(targets.size() - 5);  // "12.000\n" becomes "12"
  std::ofstream(dir / "targets.csv", std::ios::binary | std::ios::trunc) << targets;
  EXPECT_EQ(refusal_of([&] { RecordingStream stream(dir); }),
            (dir / "targets.csv").string() +
                ": its last line: no line end: the file is cut short? (every line of a recording's CSV ends with LF or CR LF)");
  EXPECT_EQ(refusal_of([&] { read_recording(dir); }).find((dir / "targets.csv").string() + ": its last line"), 0u);
  std::ofstream(dir / "targets.csv", std::ios::binary | std::ios::app) << "\r\n";  // CR LF ends it too
  EXPECT_EQ(refusal_of([&] { RecordingStream stream(dir); }), "accepted");
}

TEST_F(RecordingStreamFiles, RowsComeInOrderAndTargetsCycleByCycle) {
  RecordingStream stream(written());
  std::vector<double> ego_x_m;
  for (EgoSample s; stream.ego().next(s);) ego_x_m.push_back(s.x_m);
  EXPECT_EQ(ego_x_m, (std::vector<double>{0.0, 2.0, 4.0}));
  std::size_t object = 9;
  AnnotatedBox box;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(stream.boxes().next(object, box));
    EXPECT_EQ(object, 0u);
    EXPECT_DOUBLE_EQ(box.x_m, 20.0 + k);
    EXPECT_EQ(box.line, k + 2);  // line 1 is the header
  }
  EXPECT_FALSE(stream.boxes().next(object, box));
  stream.boxes().finish();
  std::vector<RecordedTarget> targets;
  stream.targets().read_cycle(0, 0.0, -1, targets);
  ASSERT_EQ(targets.size(), 2u);
  EXPECT_DOUBLE_EQ(targets[1].range_m, 16.0);
  stream.targets().read_cycle(1, 0.04, -1, targets);
  EXPECT_EQ(targets.size(), 2u);  // cycle 1 has none
  stream.targets().read_cycle(2, 0.08, -1, targets);
  ASSERT_EQ(targets.size(), 3u);
  EXPECT_EQ(targets[2].cycle, 2);
  EXPECT_EQ(targets[2].id, 1);
  EXPECT_NO_THROW(stream.targets().finish());
}

TEST_F(RecordingStreamFiles, TargetsOfACycleSkippedOrNotReadAreRefusedAtFinish) {
  const fs::path dir = written();
  {
    RecordingStream stream(dir);
    std::vector<RecordedTarget> targets;
    stream.targets().read_cycle(0, 0.0, -1, targets);
    stream.targets().read_cycle(1, 0.04, -1, targets);
    // Stopped before cycle 2: its row (line 4) is left over.
    EXPECT_EQ(refusal_of([&] { stream.targets().finish(); }),
              (dir / "targets.csv").string() + ": line 4, column 'cycle': cycle 2 was not read: cycles must be asked for "
                                               "in order");
  }
  rec_.targets[2].cycle = 1;
  rec_.targets[2].t_s = 0.04;
  const fs::path skipped = written();
  RecordingStream stream(skipped);
  std::vector<RecordedTarget> targets;
  stream.targets().read_cycle(0, 0.0, -1, targets);
  stream.targets().read_cycle(2, 0.08, -1, targets);  // cycle 1 skipped: its row is not taken for cycle 2
  EXPECT_EQ(targets.size(), 2u);
  EXPECT_NE(refusal_of([&] { stream.targets().finish(); }).find("line 4, column 'cycle': cycle 1 was not read"),
            std::string::npos);
}

TEST_F(RecordingStreamFiles, AnEgoLogWithoutCycleTimeTakesAnySpacingButNeedsARow) {
  const fs::path log = dir_ / "ego_log.csv";
  std::ofstream(log) << "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n0,0,0,0,0,0\n0.5,1,0,0,2,0\n3.0,6,0,0,2,0\n";
  EgoRowReader any_spacing(log, EgoLogSpacing{});
  int rows = 0;
  for (EgoSample s; any_spacing.next(s);) ++rows;
  EXPECT_EQ(rows, 3);
  // With a cycle time of 0.04 s, 0.5 s is a gap (more than 1.5 cycles).
  EXPECT_EQ(refusal_of([&] {
              EgoRowReader per_cycle(log, EgoLogSpacing{0.04});
              for (EgoSample s; per_cycle.next(s);) {
              }
            }),
            log.string() + ": line 3, column 't_s': gap of 0.500000 s after the previous row (cycle time 0.04 s): the "
                           "ego log must have one row per sensor cycle");
  std::ofstream(log, std::ios::trunc) << "t_s,x_m,y_m,yaw_rad,speed_mps,yaw_rate_radps\n";
  EXPECT_EQ(refusal_of([&] {
              EgoRowReader empty(log, EgoLogSpacing{});
              EgoSample s;
              empty.next(s);
            }),
            log.string() + ": line 1: the ego log has no rows");
}

TEST_F(RecordingStreamFiles, BoxesOfOneObjectMustFollowInTime) {
  const fs::path boxes = dir_ / "objects.csv";
  const std::vector<RecordingObject> objects = {{"car1", "passenger_car", 4.5, 1.8}, {"car2", "passenger_car", 4.5, 1.8}};
  std::ofstream(boxes) << "t_s,object,x_m,y_m,yaw_rad,speed_mps\n0,car1,1,0,0,0\n0.04,car1,2,0,0,0\n0.04,car1,3,0,0,0\n";
  BoxRowReader reader(boxes, objects);
  std::size_t object = 0;
  AnnotatedBox box;
  ASSERT_TRUE(reader.next(object, box));
  ASSERT_TRUE(reader.next(object, box));
  EXPECT_EQ(refusal_of([&] { reader.next(object, box); }),
            boxes.string() + ": line 4, column 't_s': time 0.04 s of object 'car1' does not follow its previous row's "
                             "0.04 s (line 3)");
  // Every listed object needs a row.
  std::ofstream(boxes, std::ios::trunc) << "t_s,object,x_m,y_m,yaw_rad,speed_mps\n0,car2,1,0,0,0\n";
  BoxRowReader only_car2(boxes, objects);
  while (only_car2.next(object, box)) EXPECT_EQ(object, 1u);
  EXPECT_EQ(refusal_of([&] { only_car2.finish(); }), boxes.string() + ": object 'car1' of recording.json has no rows");
}

}  // namespace rcsim::recording_stream_test
