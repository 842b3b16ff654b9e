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
  // A writer is in WAL mode while it writes (readers never block it); the last connection that
  // may write switches the file back to a rollback journal as it closes (issue 53: a finished
  // report in WAL mode could not be read by sqlite3 on read-only storage, which needs a -shm
  // beside it). While another connection has the file open the switch is left to it.
  ~ReportDatabase() { finish_journal(); }
  ReportDatabase(const ReportDatabase&) = delete;
  ReportDatabase& operator=(const ReportDatabase&) = delete;

 private:
  void finish_journal() noexcept;
};

// What the store throws when the file system or SQLite fails under it (a full disk, a lock).
using StoreError = SQLite::Exception;

}  // namespace rcsim::replay
