// What stands between a replay and its sink (replay/run/run_sink_wrapper.cpp): nothing in the
// product, so the sink itself is used; a wrapper set by a test binary wraps every run's sink.
#include "replay/run/run_sink_wrapper.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace rcsim::run_sink_wrapper_test {

// Counts the cycles it passes on.
class CountingSink final : public replay::ReplaySink {
 public:
  explicit CountingSink(replay::ReplaySink& inner) : inner_(inner) {}
  void begin_run(const Recording& recording, const replay::ImportedScene& scene, const Scene& simulated_scene,
                 const replay::ReplayOptions& options) override {
    inner_.begin_run(recording, scene, simulated_scene, options);
  }
  void add_cycle(const replay::CycleComparison& cycle) override {
    ++cycles;
    inner_.add_cycle(cycle);
  }
  void end_run(const replay::ReplaySummary& summary) override { inner_.end_run(summary); }
  int cycles = 0;

 private:
  replay::ReplaySink& inner_;
};

TEST(RunSinkWrapper, WithoutAWrapperTheSinkItselfIsUsed) {
  replay::DiscardingSink inner;
  std::unique_ptr<replay::ReplaySink> keep;
  EXPECT_EQ(&replay::wrapped_run_sink(inner, keep), &inner);
  EXPECT_EQ(keep, nullptr);
}

TEST(RunSinkWrapper, AWrapperSetOnceWrapsEachRunsSinkAndCanBeCleared) {
  int wrapped = 0;
  replay::set_run_sink_wrapper([&wrapped](replay::ReplaySink& inner) {
    ++wrapped;
    return std::make_unique<CountingSink>(inner);
  });
  replay::DiscardingSink inner;
  std::unique_ptr<replay::ReplaySink> keep;
  replay::ReplaySink& sink = replay::wrapped_run_sink(inner, keep);
  EXPECT_NE(&sink, &inner);
  EXPECT_EQ(&sink, keep.get());  // owned by the caller's `keep`
  sink.add_cycle(replay::CycleComparison{});
  sink.add_cycle(replay::CycleComparison{});
  EXPECT_EQ(dynamic_cast<CountingSink&>(sink).cycles, 2);
  std::unique_ptr<replay::ReplaySink> keep_second;
  replay::wrapped_run_sink(inner, keep_second);
  EXPECT_EQ(wrapped, 2);  // once a run

  replay::set_run_sink_wrapper({});  // the rest of this process replays as the product does
  std::unique_ptr<replay::ReplaySink> keep_none;
  EXPECT_EQ(&replay::wrapped_run_sink(inner, keep_none), &inner);
}

}  // namespace rcsim::run_sink_wrapper_test
