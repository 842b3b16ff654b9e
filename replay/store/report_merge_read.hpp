#pragma once
// What `rcsim merge` (report_merge.cpp) reads of a report database before it writes anything: its
// header checked, the identities of its runs, its benches, its campaign and criteria, and whether
// those agree across the merge; with the helpers that compare SQL values exactly and show them.
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "replay/store/report_database.hpp"

namespace rcsim::replay::merge_read {

// An SQL identifier, quoted.
std::string quoted(const std::string& identifier);
// The columns of a table of the database's main schema, in their order.
std::vector<std::string> table_columns(SQLite::Database& db, const std::string& table);
std::string join(const std::vector<std::string>& items, const std::string& separator);
// A value as a person reads it; reals in the shortest text that reads back to the same double.
std::string display(const SQLite::Column& v);
// A value exactly, with its type: equal texts are equal values.
std::string exact(const SQLite::Column& v);

enum class Header { empty, report };

// Refuses, naming the file, what is not an rcsim report of this schema version; an empty
// database (no tables, no header) is Header::empty.
Header check_header(SQLite::Database& db, const std::string& path);

// An SQLite failure on the file as an InputError naming it ("not an SQLite database" for one that
// is not).
[[noreturn]] void throw_named(const SQLite::Exception& e, const std::string& path);

// Refuses, naming it, a path that is missing or not a regular file.
void check_regular_file(const std::string& path);

// An input opened read-only (merge_files::read_only_uri: never written), its header checked.
std::unique_ptr<ReportDatabase> open_input(const std::string& path, Header& header);

// The campaign a database belongs to and its criteria (schema v5), as stored.
struct CampaignRows {
  std::optional<std::pair<std::string, std::string>> campaign;  // name, manifest
  std::vector<std::string> criteria_exact;                      // every column, by criterion
  std::vector<std::string> criteria_text;                       // as a person reads them
};

struct StoredRun {
  std::int64_t run_id = 0;
  std::string key, recording_name;  // key: RunIdentity::key()
  std::int64_t seed = 0;
};

// What a merge reads of a database before it writes.
struct Snapshot {
  std::string file;
  std::vector<StoredRun> runs;                                // by run id
  std::vector<std::pair<std::int64_t, std::string>> benches;  // id, fingerprint (its rows, its id aside)
  CampaignRows campaign;
};
Snapshot read_snapshot(SQLite::Database& db, const std::string& file);

// The campaign and criteria every database of the merge must agree on: those of the first
// database checked that has them (the output's, when it has them). A disagreement is refused,
// naming the file, the one it disagrees with and the first difference.
class CampaignAgreement {
 public:
  void check(const CampaignRows& rows, const std::string& file);

 private:
  std::optional<std::pair<std::string, std::string>> campaign_;
  std::string campaign_file_;
  std::optional<CampaignRows> criteria_;
  std::string criteria_file_;
};

// The first top-level field (in the kept manifest's order) in which a manifest differs from the
// kept one, as `field "recordings": ["c"] against ["a","b"]`, its value first; empty if they are
// equal as JSON.
std::string first_manifest_difference(const std::string& theirs, const std::string& kept);

}  // namespace rcsim::replay::merge_read
