// rcsim export REPORT.sqlite --run N --table cycles|targets|objects [--format csv|jsonl] [-o FILE]:
// one run's per-cycle, per-target or per-object rows as plain text, decoded from the report's
// compact blocks (schemas/report-database.md), for sqlite3, pandas or a spreadsheet.
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cli/commands.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "replay/report/mcap_replay.hpp"
#include "replay/store/decoded_rows.hpp"
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
  std::string clock = "run";  // --format mcap: run | log
};

// A CSV field: numbers as the shortest text that reads back to the same double, texts quoted
// where they hold a comma, a quote or a line end (RFC 4180); nothing is an empty field.
std::string csv_field(const replay::DecodedValue& v) {
  if (std::holds_alternative<std::monostate>(v)) return "";
  if (const auto* number = std::get_if<std::int64_t>(&v)) return std::to_string(*number);
  if (const auto* real = std::get_if<double>(&v)) return nlohmann::json(*real).dump();
  const std::string& text = std::get<std::string>(v);
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

class RowWriter {
 public:
  RowWriter(std::ostream& out, bool csv, const std::vector<replay::DecodedColumn>& columns) : out_(out), csv_(csv), columns_(columns) {
    if (!csv_) return;
    for (std::size_t i = 0; i < columns_.size(); ++i) out_ << (i ? "," : "") << columns_[i].name;
    out_ << '\n';
  }
  void write(const std::vector<replay::DecodedValue>& row) {
    if (csv_) {
      for (std::size_t i = 0; i < row.size(); ++i) out_ << (i ? "," : "") << csv_field(row[i]);
      out_ << '\n';
    } else {
      nlohmann::ordered_json line = nlohmann::ordered_json::object();
      for (std::size_t i = 0; i < row.size(); ++i) line[columns_[i].name] = replay::decoded_value_json(row[i]);
      out_ << line.dump() << '\n';
    }
    ++rows_;
  }
  long long rows() const { return rows_; }

 private:
  std::ostream& out_;
  bool csv_;
  const std::vector<replay::DecodedColumn>& columns_;
  long long rows_ = 0;
};

// What reading the report throws (SQLite's "malformed", a damaged block's message) is bad input,
// named by the file (exit status 2), as `rcsim report` says it.
template <class Read>
auto reading(const std::string& db_path, Read&& read) {
  try {
    return read();
  } catch (const InputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(db_path, "", e.what());
  }
}

long long export_rows(replay::ReportDatabase& db, const ExportArgs& args, std::ostream& out) {
  const replay::DecodedTable table = *replay::decoded_table_from_name(args.table);
  RowWriter writer(out, args.format == "csv", replay::decoded_columns(table));
  return reading(args.db_path, [&] {
    replay::for_each_decoded_row(db, table, args.run_id, {}, [&](const auto& row) { writer.write(row); });
    return writer.rows();
  });
}

// One run as an MCAP file for Foxglove (schemas/mcap-replay.md), written atomically.
void export_mcap(const ExportArgs& args) {
  if (args.output.empty()) throw CLI::ValidationError("--output", "--format mcap writes a binary file: name it with -o FILE.mcap");
  check_output_file(args.output);  // before any work
  const auto db = replay::open_report_database_for_reading(args.db_path);
  (void)replay::report::select_runs(*db, args.db_path, {args.run_id}, 1);  // an unknown run is refused by name
  AtomicFileWriter file(args.output);
  const replay::McapClock clock = args.clock == "log" ? replay::McapClock::log : replay::McapClock::run;
  replay::McapReplayCounts counts;
  try {
    counts = reading(args.db_path, [&] { return replay::write_run_mcap(*db, args.run_id, file.stream(), clock); });
  } catch (const std::invalid_argument& e) {
    throw InputError(args.db_path, fmt::format("run {}", args.run_id), e.what());
  }
  file.commit();
  std::cerr << fmt::format("rcsim export: run {} as MCAP, {} cycles of {} sensor(s), {} messages, {} bytes written to {}\n",
                           args.run_id, counts.cycles, counts.sensors, counts.messages, counts.bytes, args.output);
}

void run_export(const ExportArgs& args) {
  if (args.format == "mcap") return export_mcap(args);
  if (args.table.empty()) throw CLI::ValidationError("--table", "is required for --format " + args.format + ": cycles, targets or objects");
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
                                 "from the report's compact storage; or the whole run as MCAP for Foxglove");
  cmd->add_option("REPORT_DB", args->db_path, "report database (rcsim-report, SQLite)")->required();
  cmd->add_option("--run", args->run_id, "run id (rcsim report and the replay's first line name it)")->required();
  cmd->add_option("--table", args->table,
                  "cycles (figures per cycle and sensor), targets (every recorded and simulated target) or objects "
                  "(the annotated boxes per cycle); not with --format mcap")
      ->check(CLI::IsMember({"cycles", "targets", "objects"}));
  cmd->add_option("--format", args->format,
                  "csv (with a header row), jsonl (one JSON object per line), or mcap (the whole run: targets, boxes, "
                  "transforms, view fields and figures for Foxglove, schemas/mcap-replay.md; needs -o)")
      ->check(CLI::IsMember({"csv", "jsonl", "mcap"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "file to write (atomically); default: standard output");
  cmd->add_option("--clock", args->clock,
                  "(--format mcap) run: times from the recording's start; log: the log's own clock (the recording's "
                  "source.first_timestamp_ns added), so the export overlays the original log in Foxglove")
      ->check(CLI::IsMember({"run", "log"}))
      ->capture_default_str();
  cmd->callback([args] {
    if (args->clock != "run" && args->format != "mcap") throw CLI::ValidationError("--clock", "is for --format mcap");
    run_export(*args);
  });
}

}  // namespace rcsim::cli
