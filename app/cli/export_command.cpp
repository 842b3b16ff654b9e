// rcsim export REPORT.sqlite --run N --table cycles|targets|objects [--format csv|jsonl] [-o FILE]:
// one run's per-cycle, per-target or per-object rows as plain text, decoded from the report's
// compact blocks (schemas/report-database.md), for sqlite3, pandas or a spreadsheet.
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "metrics/target_class.hpp"
#include "replay/store/report_reader.hpp"
#include "replay/store/report_store.hpp"
#include "replay/store/run_rows.hpp"

namespace rcsim::cli {

namespace {

struct ExportArgs {
  std::string db_path;
  std::int64_t run_id = 0;
  std::string table;
  std::string format = "csv";
  std::string output;  // empty: stdout
};

// One row as named values: a number, a text, or nothing (CSV: empty; JSON Lines: null).
using Value = std::optional<nlohmann::ordered_json>;
using Row = std::vector<std::pair<const char*, Value>>;

constexpr std::nullopt_t kNone = std::nullopt;
Value real(double v) { return std::isfinite(v) ? Value(v) : Value(kNone); }
Value whole(long long v) { return Value(v); }
Value index_or_none(int v) { return v < 0 ? Value(kNone) : Value(v); }

Row cycle_row(std::int64_t run_id, const replay::StoredCycle& c) {
  const auto classes = c.classes.value_or(replay::StoredCycle::Classes{});
  const bool has = c.classes.has_value();
  return {{"run_id", whole(run_id)},
          {"cycle", whole(c.cycle)},
          {"sensor", whole(c.sensor)},
          {"t_s", real(c.t_s)},
          {"sensor_x_m", c.X_WS ? real(c.X_WS->x_m) : Value(kNone)},
          {"sensor_y_m", c.X_WS ? real(c.X_WS->y_m) : Value(kNone)},
          {"sensor_yaw_rad", c.X_WS ? real(c.X_WS->yaw_rad) : Value(kNone)},
          {"n_recorded", whole(c.n_recorded)},
          {"n_simulated", whole(c.n_simulated)},
          {"n_assigned", whole(c.n_assigned)},
          {"gospa_m", real(c.gospa_m)},
          {"gospa_localisation_mp", real(c.gospa_localisation_mp)},
          {"gospa_missed_mp", real(c.gospa_missed_mp)},
          {"gospa_false_mp", real(c.gospa_false_mp)},
          {"ospa_m", real(c.ospa_m)},
          {"merge_recorded", whole(c.merge_recorded)},
          {"merge_simulated", whole(c.merge_simulated)},
          {"merge_matched", whole(c.merge_matched)},
          {"n_object_recorded", has ? whole(classes.n_object_recorded) : Value(kNone)},
          {"n_object_simulated", has ? whole(classes.n_object_simulated) : Value(kNone)},
          {"n_background_recorded", has ? whole(classes.n_background_recorded) : Value(kNone)},
          {"n_background_simulated", has ? whole(classes.n_background_simulated) : Value(kNone)},
          {"gospa_object_m", has ? real(classes.gospa_object_m) : Value(kNone)},
          {"ospa_object_m", has ? real(classes.ospa_object_m) : Value(kNone)}};
}

Row target_row(std::int64_t run_id, const replay::StoredTarget& t) {
  const Vec2 p_ST_S = t.p_ST_S();
  return {{"run_id", whole(run_id)},
          {"cycle", whole(t.cycle)},
          {"sensor", whole(t.sensor)},
          {"origin", Value(t.simulated ? "simulated" : "recorded")},
          {"idx", whole(t.idx)},
          {"track_id", index_or_none(t.track_id)},
          {"range_m", real(t.range_m)},
          {"azimuth_rad", real(t.azimuth_rad)},
          {"range_rate_mps", real(t.range_rate_mps)},
          {"amplitude_db", real(t.amplitude_db)},
          {"x_s_m", real(p_ST_S.x())},
          {"y_s_m", real(p_ST_S.y())},
          {"object", index_or_none(t.object)},
          {"match_idx", index_or_none(t.match_idx)},
          {"merge_artefact", whole(t.merge_artefact ? 1 : 0)},
          {"target_class",
           t.target_class ? Value(std::string(metrics::target_class_name(*t.target_class))) : Value(kNone)},
          {"x_o_m", t.p_OT_O ? real(t.p_OT_O->x()) : Value(kNone)},
          {"y_o_m", t.p_OT_O ? real(t.p_OT_O->y()) : Value(kNone)},
          {"rcs_dbsm", real(t.rcs_dbsm)},
          {"snr_db", real(t.snr_db)},
          {"elevation_rad", real(t.elevation_rad)}};
}

Row object_row(std::int64_t run_id, const replay::StoredObjectState& s) {
  return {{"run_id", whole(run_id)}, {"cycle", whole(s.cycle)},     {"object", whole(s.object)},
          {"x_m", real(s.X_WO.x_m)},    {"y_m", real(s.X_WO.y_m)},       {"yaw_rad", real(s.X_WO.yaw_rad)}};
}

// A CSV field: numbers as the shortest text that reads back to the same double, texts quoted
// where they hold a comma, a quote or a line end (RFC 4180).
std::string csv_field(const Value& v) {
  if (!v) return "";
  if (!v->is_string()) return v->dump();
  const std::string text = v->get<std::string>();
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

class RowWriter {
 public:
  RowWriter(std::ostream& out, bool csv) : out_(out), csv_(csv) {}
  void write(const Row& row) {
    if (csv_) {
      if (!header_written_) {
        for (std::size_t i = 0; i < row.size(); ++i) out_ << (i ? "," : "") << row[i].first;
        out_ << '\n';
        header_written_ = true;
      }
      for (std::size_t i = 0; i < row.size(); ++i) out_ << (i ? "," : "") << csv_field(row[i].second);
      out_ << '\n';
    } else {
      nlohmann::ordered_json line = nlohmann::ordered_json::object();
      for (const auto& [name, value] : row) line[name] = value ? *value : nlohmann::ordered_json();
      out_ << line.dump() << '\n';
    }
    ++rows_;
  }
  long long rows() const { return rows_; }

 private:
  std::ostream& out_;
  bool csv_;
  bool header_written_ = false;
  long long rows_ = 0;
};

long long export_rows(replay::ReportDatabase& db, const ExportArgs& args, std::ostream& out) {
  RowWriter writer(out, args.format == "csv");
  const std::int64_t run = args.run_id;
  if (args.table == "cycles") {
    replay::for_each_cycle(db, run, {}, [&](const replay::StoredCycle& c) { writer.write(cycle_row(run, c)); });
  } else if (args.table == "targets") {
    replay::for_each_target(db, run, {}, [&](const replay::StoredTarget& t) { writer.write(target_row(run, t)); });
  } else {
    replay::for_each_object_state(db, run, {},
                                  [&](const replay::StoredObjectState& s) { writer.write(object_row(run, s)); });
  }
  return writer.rows();
}

void run_export(const ExportArgs& args) {
  if (!args.output.empty()) check_output_file(args.output);  // before any work
  const auto db = replay::open_report_database_for_reading(args.db_path);
  (void)replay::report::select_runs(*db, args.db_path, {args.run_id}, 1);  // an unknown run is refused by name
  const replay::report::RunData run = replay::report::load_run(*db, args.run_id);
  if (!run.info.has_targets() && args.table != "cycles") {
    throw InputError(args.db_path, fmt::format("run {}", args.run_id),
                     fmt::format("stored with --store summary: it keeps no {} (only --table cycles)", args.table));
  }
  if (args.output.empty()) {
    export_rows(*db, args, std::cout);
    std::cout.flush();
    return;
  }
  AtomicFileWriter file(args.output);
  const long long rows = export_rows(*db, args, file.stream());
  file.commit();
  std::cerr << fmt::format("rcsim export: {} rows of run {}'s {} written to {}\n", rows, args.run_id, args.table,
                           args.output);
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  auto* cmd = app.add_subcommand("export",
                                 "one run's per-cycle, per-target or per-object rows as CSV or JSON Lines, decoded "
                                 "from the report's compact storage");
  cmd->add_option("REPORT_DB", args->db_path, "report database (rcsim-report, SQLite)")->required();
  cmd->add_option("--run", args->run_id, "run id (rcsim report and the replay's first line name it)")->required();
  cmd->add_option("--table", args->table,
                  "cycles (figures per cycle and sensor), targets (every recorded and simulated target) or objects "
                  "(the annotated boxes per cycle)")
      ->required()
      ->check(CLI::IsMember({"cycles", "targets", "objects"}));
  cmd->add_option("--format", args->format, "csv (with a header row) or jsonl (one JSON object per line)")
      ->check(CLI::IsMember({"csv", "jsonl"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "file to write (atomically); default: standard output");
  cmd->callback([args] { run_export(*args); });
}

}  // namespace rcsim::cli
