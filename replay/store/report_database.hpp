#pragma once
// The report database, owned by the store (replay/store/): every other layer and tool holds a
// ReportDatabase, opens it through report_store.hpp and asks the store's functions; none of them
// names SQLite or writes SQL (tests/architecture/store_owns_sql_test.cpp).
#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>

namespace rcsim::replay {

class ReportDatabase : public SQLite::Database {
 public:
  using SQLite::Database::Database;
};

// What the store throws when the file system or SQLite fails under it (a full disk, a lock).
using StoreError = SQLite::Exception;

}  // namespace rcsim::replay
