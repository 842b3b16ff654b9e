#pragma once
// Migrating a report of an older schema (report_store.cpp opens it for writing).
#include <SQLiteCpp/Database.h>

namespace rcsim::replay {

// Version 3 to 4: the rows of `cycles`, `targets` and `object_states` packed into blocks
// (schemas/report-database.md, "Blocks"), in the caller's transaction.
void convert_row_tables_to_blocks(SQLite::Database& db);

}  // namespace rcsim::replay
