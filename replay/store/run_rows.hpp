#pragma once
// The per-cycle rows of a run in the report database (schemas/report-database.md) as a reader
// sees them, whatever their storage: one row per cycle and sensor, every recorded and simulated
// target, the annotated boxes per cycle. Every reader of these rows (the report's figures, the
// golden run, tests) goes through here, never through SQL on the tables that hold them.
//
// They are stored (schema v4) packed into blocks of up to kBlockCycles consecutive cycles per
// sensor, one BLOB per column (packed_columns.hpp): the targets' reals as float32, every other
// real exactly.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "common/pose2.hpp"
#include "metrics/target_class.hpp"

namespace rcsim::replay {

// What a run keeps (`rcsim replay --store`): full keeps every target, the annotated boxes and the
// sensor poses; summary the per-cycle figures and everything per run, object and sensor.
enum class StoreLevel { full, summary };
std::string_view store_level_name(StoreLevel level);           // "full", "summary"
StoreLevel store_level_from_name(std::string_view name);        // throws std::invalid_argument

// The cycles first..last, both included.
struct CycleSpan {
  int first = 0;
  int last = std::numeric_limits<int>::max();
  bool contains(int cycle) const { return cycle >= first && cycle <= last; }
};

// One cycle and sensor: the comparison of its recorded and simulated target lists.
struct StoredCycle {
  int cycle = 0, sensor = 0;
  double t_s = 0.0;           // recording time
  std::optional<Pose2> X_WS;  // sensor pose in the world
  int n_recorded = 0, n_simulated = 0, n_assigned = 0;
  double gospa_m = 0.0, gospa_localisation_mp = 0.0, gospa_missed_mp = 0.0, gospa_false_mp = 0.0, ospa_m = 0.0;
  int merge_recorded = 0, merge_simulated = 0, merge_matched = 0;
  // The real-drive figures (schema v3); absent in runs stored before.
  struct Classes {
    int n_object_recorded = 0, n_object_simulated = 0, n_background_recorded = 0, n_background_simulated = 0;
    double gospa_object_m = 0.0, ospa_object_m = 0.0;  // on the object targets only
  };
  std::optional<Classes> classes;
};

// One recorded or simulated target of a cycle and sensor.
struct StoredTarget {
  int cycle = 0, sensor = 0;
  bool simulated = false;
  int idx = 0;        // position in its list of that cycle, sensor and origin
  int track_id = -1;  // -1: the recording has no ids
  double range_m = 0.0, azimuth_rad = 0.0, range_rate_mps = 0.0, amplitude_db = 0.0;
  int object = -1;     // the annotated object it belongs to, -1: none
  int match_idx = -1;  // idx of the GOSPA-assigned target of the other origin, -1: none
  bool merge_artefact = false;
  std::optional<metrics::TargetClass> target_class;  // absent in runs stored before schema v3
  std::optional<Vec2> p_OT_O;                        // offset in the object's frame (object >= 0, v3)
  // The recording's optional columns; NaN where absent.
  double rcs_dbsm = std::numeric_limits<double>::quiet_NaN(), snr_db = std::numeric_limits<double>::quiet_NaN(),
         elevation_rad = std::numeric_limits<double>::quiet_NaN();

  Vec2 p_ST_S() const;  // Cartesian, sensor frame: range (cos, sin)(azimuth)
};

// One annotated (smoothed) box in one cycle, world frame.
struct StoredObjectState {
  int cycle = 0, object = 0;
  Pose2 X_WO;
};

// The targets of one cycle and sensor, each list by idx.
struct StoredTargetList {
  int cycle = 0, sensor = 0;
  std::vector<StoredTarget> recorded, simulated;
};

inline constexpr int kBlockCycles = 256;

// The store level a run was written with (runs.store); full for runs stored before v4.
StoreLevel run_store_level(SQLite::Database& db, std::int64_t run_id);

// The rows of `run_id` within `span`, in cycle order; per cycle by sensor, then recorded before
// simulated and by idx (targets) or as stored, by object (boxes). A summary run has cycles but
// neither targets nor boxes, and its cycles no sensor pose.
void for_each_cycle(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                    const std::function<void(const StoredCycle&)>& visit);
void for_each_target_list(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                          const std::function<void(const StoredTargetList&)>& visit);
void for_each_target(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                     const std::function<void(const StoredTarget&)>& visit);
void for_each_object_state(SQLite::Database& db, std::int64_t run_id, CycleSpan span,
                           const std::function<void(const StoredObjectState&)>& visit);

// Writes the per-cycle rows of one run, which the caller has inserted into `runs`, into their
// blocks, inside the caller's transaction. A sensor's cycles come in increasing order (a gap
// starts a new block); the other sensors' may interleave. A summary writer keeps the cycles
// without their sensor poses, and no targets or boxes. `cutoff_m` and `order_p` are the run's
// GOSPA parameters: they only make the stored figures smaller, never different.
class RunRowWriter {
 public:
  RunRowWriter(SQLite::Database& db, std::int64_t run_id, StoreLevel store, double cutoff_m, double order_p);
  ~RunRowWriter();
  RunRowWriter(const RunRowWriter&) = delete;
  RunRowWriter& operator=(const RunRowWriter&) = delete;

  // One cycle and sensor with its targets; in a full run the cycle needs its sensor pose.
  void add_cycle(const StoredCycle& cycle, const std::vector<StoredTarget>& recorded,
                 const std::vector<StoredTarget>& simulated);
  // The boxes of one cycle (every cycle, also when there is none); ignored in a summary run.
  void add_object_states(int cycle, const std::vector<StoredObjectState>& states);
  // Stores the blocks still open; call once, after the last cycle.
  void finish();

 private:
  struct SensorBlock {
    std::vector<StoredCycle> cycles;
    std::vector<StoredTargetList> targets;
  };
  // A sensor's open block into its rows: the cycles' columns, then (a full run) the targets'.
  void flush(int sensor, SensorBlock& block);
  void write_cycle_block(int sensor, const std::vector<StoredCycle>& cycles);
  void write_target_block(int sensor, int first_cycle, const std::vector<StoredTargetList>& targets);
  void flush_object_states();

  SQLite::Database& db_;
  std::int64_t run_id_;
  StoreLevel store_;
  double half_cutoff_p_, order_p_;
  std::map<int, SensorBlock> open_;
  std::vector<std::vector<StoredObjectState>> object_cycles_;
  int object_first_cycle_ = 0;
  std::unique_ptr<SQLite::Statement> insert_cycles_, insert_targets_, insert_objects_;
};

}  // namespace rcsim::replay
