#pragma once
// Stores a bench (replay/evaluate/bench.hpp) in the report database: one bench_runs row and its
// bench_rows, in one transaction (schemas/report-database.md).
#include <SQLiteCpp/SQLiteCpp.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "replay/evaluate/bench.hpp"

namespace rcsim::replay {

// Returns the new bench_id.
std::int64_t store_bench(SQLite::Database& db, const BenchOptions& options, const std::string& machine,
                         const std::vector<BenchRow>& rows);

// The parameters stored with a bench (JSON): metric parameters, the timing rule and the levels.
nlohmann::ordered_json bench_parameters_json(const BenchOptions& options);

}  // namespace rcsim::replay
