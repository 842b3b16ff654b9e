#pragma once
// The report database's schema, step by step (schemas/report-database.md): each version's SQL,
// run in order by open_report_database (report_store.cpp) on a new report or one to migrate.
namespace rcsim::replay {

extern const char* const kReportSchemaSql;       // version 1: runs, summaries and the row tables
extern const char* const kBenchSchemaSql;        // version 2: bench_runs, bench_rows
extern const char* const kRealDriveSchemaSql;    // version 3: the real-drive tables and columns
extern const char* const kBlockSchemaSql;        // version 4: the block tables
extern const char* const kDropRowTablesSql;      // version 4: the row tables, once converted
extern const char* const kCampaignSchemaSql;     // version 5: campaign, criteria
extern const char* const kObjectRangeTargetsSql;  // version 6: object targets per range bin

}  // namespace rcsim::replay
