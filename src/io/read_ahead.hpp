#pragma once
// Rows read ahead on a thread of their own: a reader function (parsing and checking one file's
// rows) runs on its own thread and hands its rows over in blocks through a bounded queue, so that
// reading a file overlaps the work of the thread that uses its rows (rcsim replay reads objects.csv
// and targets.csv so, beside the simulation). Memory stays bounded (kMaxBlocks blocks of
// kBlockRows rows ahead). An exception of the reader reaches the consumer where it happened: after
// the rows read before it, never earlier. The rows and their order are those of the reader alone.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace rcsim {

template <class Row>
class ReadAhead {
 public:
  static constexpr std::size_t kBlockRows = 2048, kMaxBlocks = 4;

  // read(row): the next row, false at the end; may throw.
  explicit ReadAhead(std::function<bool(Row&)> read) : read_(std::move(read)), thread_([this] { produce(); }) {}
  ReadAhead(const ReadAhead&) = delete;
  ReadAhead& operator=(const ReadAhead&) = delete;
  ~ReadAhead() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }

  // The next row; false at the end (and from then on); rethrows the reader's exception.
  bool next(Row& row) {
    while (position_ == current_.rows.size()) {
      if (current_.error) std::rethrow_exception(current_.error);
      if (current_.last) return false;
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return !blocks_.empty(); });
      current_ = std::move(blocks_.front());
      blocks_.pop_front();
      position_ = 0;
      lock.unlock();
      changed_.notify_all();
    }
    row = std::move(current_.rows[position_++]);
    return true;
  }

 private:
  struct Block {
    std::vector<Row> rows;
    bool last = false;            // the reader has no more rows
    std::exception_ptr error;     // the reader failed after these rows
  };

  void produce() {
    for (;;) {
      Block block;
      block.rows.reserve(kBlockRows);
      try {
        Row row;
        while (block.rows.size() < kBlockRows) {
          if (!read_(row)) {
            block.last = true;
            break;
          }
          block.rows.push_back(std::move(row));
        }
      } catch (...) {
        block.error = std::current_exception();
      }
      const bool done = block.last || block.error;
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [this] { return stop_ || blocks_.size() < kMaxBlocks; });
      if (stop_) return;
      blocks_.push_back(std::move(block));
      lock.unlock();
      changed_.notify_all();
      if (done) return;
    }
  }

  std::function<bool(Row&)> read_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Block> blocks_;
  bool stop_ = false;
  Block current_;
  std::size_t position_ = 0;
  std::thread thread_;  // last: starts once everything above is constructed
};

}  // namespace rcsim
