// The report database schema (`rcsim-report` v6, schemas/report-database.md), applied by
// report_store.cpp when it creates a database: the v1 tables, the bench tables (v2), the
// real-drive additions (v3), then the v4 blocks, into which the rows of the v1 tables `cycles`,
// `targets` and `object_states` are converted (report_migration.cpp) before those are dropped,
// the campaign tables (v5) and the targets per range bin (v6). Opening a v1 to v5 database
// applies the steps it lacks, so that a migrated database has exactly the tables and columns of a
// new one.
#include "replay/store/report_schema.hpp"

namespace rcsim::replay {

// Version 1; `cycles`, `targets` and `object_states` live on only until the v4 conversion.
const char* const kReportSchemaSql = R"SQL(
CREATE TABLE IF NOT EXISTS runs (
  run_id INTEGER PRIMARY KEY,
  recording_name TEXT NOT NULL,
  recording_dir TEXT NOT NULL,
  recording_checksum TEXT NOT NULL,      -- FNV-1a 64, 16 hex digits (schemas/recording.md)
  recording_source TEXT NOT NULL,        -- JSON: the recording's provenance
  cycle_time_s REAL NOT NULL,
  cycles INTEGER NOT NULL,
  seed INTEGER NOT NULL,
  level TEXT NOT NULL,                   -- simulation output level compared (tracks)
  parameters TEXT NOT NULL,              -- JSON: metric and import parameters with their sources
  rcsim_version TEXT NOT NULL,
  created_utc TEXT NOT NULL              -- ISO 8601
) STRICT;

CREATE TABLE IF NOT EXISTS run_sensors (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  sensor INTEGER NOT NULL,               -- index in recording.json
  sensor_id TEXT NOT NULL,
  type TEXT NOT NULL,
  x_m REAL NOT NULL, y_m REAL NOT NULL, yaw_rad REAL NOT NULL,
  azimuth_half_rad REAL NOT NULL, max_range_m REAL NOT NULL,
  configuration TEXT NOT NULL,           -- the rcsim-sensor document used
  PRIMARY KEY (run_id, sensor)
) STRICT;

CREATE TABLE IF NOT EXISTS run_objects (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  object INTEGER NOT NULL,               -- index in recording.json
  object_id TEXT NOT NULL,
  class TEXT NOT NULL,                   -- also the object model used
  length_m REAL NOT NULL, width_m REAL NOT NULL,
  reflectors INTEGER NOT NULL,
  PRIMARY KEY (run_id, object)
) STRICT;

CREATE TABLE IF NOT EXISTS cycles (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  cycle INTEGER NOT NULL,
  sensor INTEGER NOT NULL,
  t_s REAL NOT NULL,
  sensor_x_m REAL NOT NULL, sensor_y_m REAL NOT NULL, sensor_yaw_rad REAL NOT NULL,
  n_recorded INTEGER NOT NULL, n_simulated INTEGER NOT NULL, n_assigned INTEGER NOT NULL,
  gospa_m REAL NOT NULL,
  gospa_localisation_mp REAL NOT NULL, gospa_missed_mp REAL NOT NULL, gospa_false_mp REAL NOT NULL,
  ospa_m REAL NOT NULL,
  merge_recorded INTEGER NOT NULL, merge_simulated INTEGER NOT NULL, merge_matched INTEGER NOT NULL,
  PRIMARY KEY (run_id, cycle, sensor)
) STRICT, WITHOUT ROWID;

CREATE TABLE IF NOT EXISTS targets (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  cycle INTEGER NOT NULL,
  sensor INTEGER NOT NULL,
  origin TEXT NOT NULL CHECK (origin IN ('recorded', 'simulated')),
  idx INTEGER NOT NULL,                  -- position in its list of that cycle and sensor
  track_id INTEGER,                      -- NULL if the recording has no ids
  range_m REAL NOT NULL, azimuth_rad REAL NOT NULL, range_rate_mps REAL NOT NULL, amplitude_db REAL NOT NULL,
  x_s_m REAL NOT NULL, y_s_m REAL NOT NULL,  -- Cartesian, sensor frame
  object INTEGER,                        -- the object it belongs to (nearest box within the gate)
  match_idx INTEGER,                     -- idx of the assigned target of the other origin
  merge_artefact INTEGER NOT NULL,       -- 1 if a merge artefact of a pair sharing a cell
  PRIMARY KEY (run_id, cycle, sensor, origin, idx)
) STRICT, WITHOUT ROWID;

CREATE TABLE IF NOT EXISTS object_states (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  cycle INTEGER NOT NULL,
  object INTEGER NOT NULL,
  x_m REAL NOT NULL, y_m REAL NOT NULL, yaw_rad REAL NOT NULL,  -- annotated box (smoothed), world
  PRIMARY KEY (run_id, cycle, object)
) STRICT, WITHOUT ROWID;

CREATE TABLE IF NOT EXISTS merge_pairs (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  cycle INTEGER NOT NULL,
  sensor INTEGER NOT NULL,
  object_a INTEGER NOT NULL, object_b INTEGER NOT NULL,
  PRIMARY KEY (run_id, cycle, sensor, object_a, object_b)
) STRICT, WITHOUT ROWID;

CREATE TABLE IF NOT EXISTS latencies (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  sensor INTEGER NOT NULL,
  object INTEGER NOT NULL,
  episode INTEGER NOT NULL,              -- 0, 1, ...: the object's detectable episodes for this sensor
  detectable_from_s REAL NOT NULL,
  first_recorded_s REAL, first_simulated_s REAL,       -- NULL: never reported
  latency_recorded_s REAL, latency_simulated_s REAL,
  PRIMARY KEY (run_id, sensor, object, episode)
) STRICT;

CREATE TABLE IF NOT EXISTS distribution_distances (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  quantity TEXT NOT NULL,
  unit TEXT NOT NULL,
  wasserstein1 REAL,                      -- NULL when either sample is empty
  kolmogorov_smirnov REAL,
  n_recorded INTEGER NOT NULL, n_simulated INTEGER NOT NULL,
  PRIMARY KEY (run_id, quantity)
) STRICT;

CREATE TABLE IF NOT EXISTS summaries (
  run_id INTEGER PRIMARY KEY REFERENCES runs(run_id) ON DELETE CASCADE,
  cycles INTEGER NOT NULL,
  targets_recorded INTEGER NOT NULL, targets_simulated INTEGER NOT NULL, targets_matched INTEGER NOT NULL,
  gospa_mean REAL NOT NULL, ospa_mean REAL NOT NULL,
  gospa_localisation_mean REAL NOT NULL, gospa_missed_mean REAL NOT NULL, gospa_false_mean REAL NOT NULL,
  merge_artefacts_recorded INTEGER NOT NULL, merge_artefacts_simulated INTEGER NOT NULL,
  merge_artefacts_matched INTEGER NOT NULL,
  latency_recorded_s REAL, latency_simulated_s REAL, latency_pairs INTEGER NOT NULL,
  residual_range_rms_m REAL NOT NULL, residual_azimuth_rms_rad REAL NOT NULL,
  residual_range_rate_rms_mps REAL NOT NULL, residual_amplitude_mean_db REAL NOT NULL,
  simulate_cpu_s REAL NOT NULL, total_wall_s REAL NOT NULL
) STRICT;
)SQL";

// Added in version 2: `rcsim bench` (speed against error, replay/evaluate/bench.hpp).
const char* const kBenchSchemaSql = R"SQL(
CREATE TABLE IF NOT EXISTS bench_runs (
  bench_id INTEGER PRIMARY KEY,
  seed INTEGER NOT NULL,
  machine TEXT NOT NULL,                 -- CPU model and logical cores the speeds were measured on
  parameters TEXT NOT NULL,              -- JSON: metric parameters, timing rule, levels and their meaning
  rcsim_version TEXT NOT NULL,
  created_utc TEXT NOT NULL              -- ISO 8601
) STRICT;

CREATE TABLE IF NOT EXISTS bench_rows (
  bench_id INTEGER NOT NULL REFERENCES bench_runs(bench_id) ON DELETE CASCADE,
  recording INTEGER NOT NULL,            -- 0, 1, ...: position of the recording in the bench
  recording_name TEXT NOT NULL,
  recording_checksum TEXT NOT NULL,      -- FNV-1a 64, 16 hex digits
  level TEXT NOT NULL,                   -- reference | noise_floor | full | no_monopulse | points_only | no_tracking
  sensor_cycles INTEGER NOT NULL,        -- cycles x sensors of the recording
  cpu_s REAL,                            -- CPU time of the timed simulation passes; NULL for noise_floor
  sensor_cycles_per_cpu_s REAL,          -- NULL for noise_floor
  gospa_mean_m REAL NOT NULL,            -- mean over sensor cycles against the recording
  targets_recorded INTEGER NOT NULL,
  targets_simulated INTEGER NOT NULL,
  targets_per_cycle_ratio REAL,          -- simulated / recorded; NULL when nothing was recorded
  merge_artefacts_recorded INTEGER NOT NULL,
  merge_artefacts_found INTEGER NOT NULL,     -- recorded artefacts the level also produced (per pair and cycle)
  merge_artefacts_missed INTEGER NOT NULL,    -- recorded - found
  merge_artefacts_spurious INTEGER NOT NULL,  -- simulated - found
  latency_difference_s REAL,             -- mean simulated - recorded confirmation latency; NULL: no paired episode
  latency_pairs INTEGER NOT NULL,
  PRIMARY KEY (bench_id, recording, level)
) STRICT;
)SQL";

// Added in version 3: real drives (docs/metrics.md). Each target's class and its offset in its
// object's frame, the recording's optional columns; per cycle and run the figures on the object
// targets and the class counts; per object and sensor the detection figures, overall and by range;
// the latency's paired difference and censored episodes (the latency and merge-artefact rules of
// version 3 are those of docs/metrics.md).
// Columns added to earlier tables are NULL in the runs stored before version 3.
const char* const kRealDriveSchemaSql = R"SQL(
ALTER TABLE targets ADD COLUMN target_class TEXT CHECK (target_class IN ('object', 'background', 'other'));
ALTER TABLE targets ADD COLUMN x_o_m REAL;          -- offset from the box centre, object frame (object not NULL)
ALTER TABLE targets ADD COLUMN y_o_m REAL;
ALTER TABLE targets ADD COLUMN rcs_dbsm REAL;       -- the recording's optional columns; NULL where absent
ALTER TABLE targets ADD COLUMN snr_db REAL;
ALTER TABLE targets ADD COLUMN elevation_rad REAL;

ALTER TABLE cycles ADD COLUMN n_object_recorded INTEGER;
ALTER TABLE cycles ADD COLUMN n_object_simulated INTEGER;
ALTER TABLE cycles ADD COLUMN n_background_recorded INTEGER;
ALTER TABLE cycles ADD COLUMN n_background_simulated INTEGER;
ALTER TABLE cycles ADD COLUMN gospa_object_m REAL;  -- GOSPA and OSPA on the object targets only
ALTER TABLE cycles ADD COLUMN ospa_object_m REAL;

ALTER TABLE summaries ADD COLUMN gospa_object_mean REAL;
ALTER TABLE summaries ADD COLUMN ospa_object_mean REAL;
ALTER TABLE summaries ADD COLUMN targets_object_recorded INTEGER;
ALTER TABLE summaries ADD COLUMN targets_object_simulated INTEGER;
ALTER TABLE summaries ADD COLUMN targets_background_recorded INTEGER;
ALTER TABLE summaries ADD COLUMN targets_background_simulated INTEGER;
ALTER TABLE summaries ADD COLUMN targets_other_recorded INTEGER;
ALTER TABLE summaries ADD COLUMN targets_other_simulated INTEGER;
ALTER TABLE summaries ADD COLUMN latency_difference_mean_s REAL;  -- over the pairs; NULL: none
ALTER TABLE summaries ADD COLUMN latency_episodes INTEGER;
ALTER TABLE summaries ADD COLUMN latency_unconfirmed_recorded INTEGER;   -- censored episodes
ALTER TABLE summaries ADD COLUMN latency_unconfirmed_simulated INTEGER;

CREATE TABLE IF NOT EXISTS object_figures (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  sensor INTEGER NOT NULL,
  object INTEGER NOT NULL,
  cycles_in_view INTEGER NOT NULL,       -- nearest box point in the sensor's field of view and range
  cycles_detected_recorded INTEGER NOT NULL, cycles_detected_simulated INTEGER NOT NULL,  -- >= 1 object target
  targets_recorded INTEGER NOT NULL, targets_simulated INTEGER NOT NULL,
  PRIMARY KEY (run_id, sensor, object)
) STRICT;

CREATE TABLE IF NOT EXISTS object_ranges (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  sensor INTEGER NOT NULL,
  object INTEGER NOT NULL,
  range_from_m REAL NOT NULL, range_to_m REAL NOT NULL,  -- bin of the nearest box point's range
  cycles_in_view INTEGER NOT NULL,
  cycles_detected_recorded INTEGER NOT NULL, cycles_detected_simulated INTEGER NOT NULL,
  PRIMARY KEY (run_id, sensor, object, range_from_m)
) STRICT;
)SQL";

// Added in version 4 (issue 19): the store level of a run, and the per-cycle rows packed into
// blocks of consecutive cycles, one BLOB per column (replay/store/packed_columns.hpp: u, z varints,
// f4 float32, x exact doubles against a prediction; a zero-length BLOB: every varint 0).
const char* const kBlockSchemaSql = R"SQL(
ALTER TABLE runs ADD COLUMN store TEXT NOT NULL DEFAULT 'full' CHECK (store IN ('full', 'summary'));

CREATE TABLE IF NOT EXISTS cycle_blocks (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  first_cycle INTEGER NOT NULL,
  sensor INTEGER NOT NULL,
  cycles INTEGER NOT NULL,               -- the block holds cycles first_cycle .. first_cycle + cycles - 1
  half_cutoff_p REAL NOT NULL,           -- c^p / 2 of the run's GOSPA: predicts the missed and false parts
  order_p REAL NOT NULL,                 -- p of the run's GOSPA: predicts GOSPA and OSPA (p = 1, 2)
  t_s BLOB NOT NULL,                     -- x, linear prediction
  sensor_x_m BLOB, sensor_y_m BLOB, sensor_yaw_rad BLOB,  -- x, linear prediction; NULL in a summary run
  n_recorded BLOB NOT NULL, n_simulated BLOB NOT NULL, n_assigned BLOB NOT NULL,  -- u
  gospa_m BLOB NOT NULL, gospa_localisation_mp BLOB NOT NULL, gospa_missed_mp BLOB NOT NULL,
  gospa_false_mp BLOB NOT NULL, ospa_m BLOB NOT NULL,  -- x
  merge_recorded BLOB NOT NULL, merge_simulated BLOB NOT NULL, merge_matched BLOB NOT NULL,  -- u
  n_object_recorded BLOB, n_object_simulated BLOB, n_background_recorded BLOB, n_background_simulated BLOB,  -- u
  gospa_object_m BLOB, ospa_object_m BLOB,  -- x; these six NULL in runs stored before v3
  PRIMARY KEY (run_id, first_cycle, sensor)
) STRICT;

CREATE TABLE IF NOT EXISTS target_blocks (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  first_cycle INTEGER NOT NULL,
  sensor INTEGER NOT NULL,
  cycles INTEGER NOT NULL,
  n_recorded BLOB NOT NULL, n_simulated BLOB NOT NULL,  -- u, per cycle; then per target, cycle by cycle,
  track_id BLOB NOT NULL,                -- recorded before simulated: z, -1 none
  range_m BLOB NOT NULL, azimuth_rad BLOB NOT NULL, range_rate_mps BLOB NOT NULL, amplitude_db BLOB NOT NULL,  -- f4
  object BLOB NOT NULL, match_idx BLOB NOT NULL,  -- z, -1 none
  flags BLOB NOT NULL,                   -- u: class (0 object, 1 background, 2 other, 3 none: before v3) + 4 merge artefact
  x_o_m BLOB NOT NULL, y_o_m BLOB NOT NULL,  -- f4, only the targets with an object and a class
  rcs_dbsm BLOB, snr_db BLOB, elevation_rad BLOB,  -- f4, NaN where absent; NULL: absent in the whole block
  PRIMARY KEY (run_id, first_cycle, sensor)
) STRICT;

CREATE TABLE IF NOT EXISTS object_state_blocks (
  run_id INTEGER NOT NULL REFERENCES runs(run_id) ON DELETE CASCADE,
  first_cycle INTEGER NOT NULL,
  cycles INTEGER NOT NULL,
  n_objects BLOB NOT NULL,               -- u, per cycle; then per box, cycle by cycle:
  object BLOB NOT NULL,                  -- u
  x_m BLOB NOT NULL, y_m BLOB NOT NULL, yaw_rad BLOB NOT NULL,  -- x, linear prediction from the object's last two
  PRIMARY KEY (run_id, first_cycle)
) STRICT;
)SQL";

// Added in version 5 (issue 20): campaigns. The campaign the runs belong to (at most one row) and
// its pass/fail criteria (replay/verdict/criteria.hpp, schemas/campaign.md); the verdicts are
// computed from these and the stored figures whenever they are needed, never stored.
const char* const kCampaignSchemaSql = R"SQL(
CREATE TABLE IF NOT EXISTS campaign (
  name TEXT NOT NULL,
  manifest TEXT NOT NULL                 -- JSON: the rcsim-campaign manifest as planned
) STRICT;

CREATE TABLE IF NOT EXISTS criteria (
  criterion INTEGER PRIMARY KEY,         -- 0, 1, ...: the order of the criteria document
  figure TEXT NOT NULL,                  -- a figure of schemas/campaign.md (gospa_mean_m, ...)
  scope TEXT NOT NULL CHECK (scope IN ('recording', 'campaign')),
  statistic TEXT NOT NULL CHECK (statistic IN ('value', 'mean', 'median', 'p95', 'min', 'max')),  -- value: per recording
  bound TEXT NOT NULL CHECK (bound IN ('max', 'min')),  -- max: passes if figure <= threshold; min: if >=
  threshold REAL NOT NULL,
  if_missing TEXT NOT NULL CHECK (if_missing IN ('fail', 'pass'))
) STRICT;
)SQL";

// Added in version 6: the targets of class object per range bin, as object_figures has them per
// object (ObjectRangeRow). NULL in the runs stored before: not known, never 0.
const char* const kObjectRangeTargetsSql = R"SQL(
ALTER TABLE object_ranges ADD COLUMN targets_recorded INTEGER;   -- object targets in those cycles; NULL before v6
ALTER TABLE object_ranges ADD COLUMN targets_simulated INTEGER;
)SQL";

// After the conversion of their rows (report_migration.cpp).
const char* const kDropRowTablesSql = R"SQL(
DROP TABLE targets;
DROP TABLE object_states;
DROP TABLE cycles;
)SQL";

}  // namespace rcsim::replay
