// The test Slurm cluster itself: an array runs, a cancelled task is redone by resubmitting its
// index, two clusters run side by side (CTest -j2 starts tests in parallel), and no daemon
// outlives the fixture. Skipped, with the reason, where Slurm cannot run (not root, no packages).
#include "end_to_end/slurm_cluster.hpp"

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app/cli/run_rcsim.hpp"
#include "scratch_dir.hpp"

namespace rcsim::testing {
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;

class SlurmClusterTest : public ScratchDirTest {
 protected:
  SlurmClusterTest() : ScratchDirTest("slurm") {}

  // A task script: marks itself partial, sleeps for good on the first run of SLOW_TASK (so that
  // it can be cancelled mid-run), then writes its result and removes the partial marker.
  fs::path write_task_script(const fs::path& out, int slow_task = -1) const {
    const auto script = dir_ / "task.sh";
    std::ofstream(script) << "#!/bin/sh\n"
                          << "out=" << out.string() << "\n"
                          << "i=$SLURM_ARRAY_TASK_ID\n"
                          << "echo partial > $out/partial_$i\n"
                          << "if [ \"$i\" = " << slow_task << " ] && [ ! -e $out/started_$i ]; then\n"
                          // scancel may signal the sleep before the shell: a killed sleep ends
                          // the task, which must not go on to look finished.
                          << "  touch $out/started_$i; sleep 600 || exit 143\n"
                          << "fi\n"
                          << "echo \"$SLURM_ARRAY_JOB_ID $SLURM_ARRAY_TASK_ID\" > $out/task_$i.txt\n"
                          << "rm $out/partial_$i\n";
    fs::permissions(script, fs::perms::owner_all, fs::perm_options::add);
    fs::create_directories(out);
    return script;
  }

  static std::string array_args(const std::string& indices, const fs::path& out, const fs::path& script) {
    return "--array=" + indices + " --output=" + (out / "slurm-%A_%a.out").string() + " " + script.string();
  }
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool alive(pid_t pid) { return ::kill(pid, 0) == 0 || errno != ESRCH; }

TEST_F(SlurmClusterTest, ArrayOfFourTasksCompletes) {
  std::string why_not;
  const auto t0 = std::chrono::steady_clock::now();
  auto cluster = SlurmCluster::start(dir_, &why_not);
  if (!cluster) GTEST_SKIP() << why_not;
  const double startup_s = seconds_since(t0);
  EXPECT_GE(cluster->cpus(), 1);
  const auto out = dir_ / "out";
  const auto script = write_task_script(out);

  const auto t1 = std::chrono::steady_clock::now();
  // A batch script may ask for memory: the node has the machine's.
  const std::string job = cluster->sbatch("--mem=512M " + array_args("0-3", out, script));
  const auto states = cluster->wait(job, seconds(60));
  const double array_s = seconds_since(t1);

  ASSERT_EQ(states.size(), 4u);
  for (int task = 0; task < 4; ++task) {
    EXPECT_EQ(states.at(task), "COMPLETED") << "task " << task;
    EXPECT_EQ(read_file(out / ("task_" + std::to_string(task) + ".txt")), job + " " + std::to_string(task) + "\n");
    EXPECT_FALSE(fs::exists(out / ("partial_" + std::to_string(task))));
  }

  const auto pids = cluster->daemon_pids();
  for (const pid_t pid : pids) EXPECT_TRUE(alive(pid));
  const auto t2 = std::chrono::steady_clock::now();
  cluster.reset();
  const double stop_s = seconds_since(t2);
  for (const pid_t pid : pids) EXPECT_FALSE(alive(pid)) << "daemon " << pid << " outlived the fixture";
  std::cout << "[ slurm    ] start-up " << startup_s << " s, 4-task array " << array_s << " s, stop " << stop_s
            << " s\n";
}

TEST_F(SlurmClusterTest, CancelledTaskIsRedoneByResubmittingIt) {
  std::string why_not;
  auto cluster = SlurmCluster::start(dir_, &why_not);
  if (!cluster) GTEST_SKIP() << why_not;
  const auto out = dir_ / "out";
  const auto script = write_task_script(out, 2);

  const std::string job = cluster->sbatch(array_args("0-3", out, script));
  const auto deadline = std::chrono::steady_clock::now() + seconds(60);
  while (!fs::exists(out / "started_2")) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline) << "task 2 never started";
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  cluster->cancel(job + "_2");
  const auto states = cluster->wait(job, seconds(60));
  ASSERT_EQ(states.size(), 4u);
  EXPECT_EQ(states.at(0), "COMPLETED");
  EXPECT_EQ(states.at(1), "COMPLETED");
  EXPECT_EQ(states.at(2), "CANCELLED");
  EXPECT_EQ(states.at(3), "COMPLETED");
  EXPECT_TRUE(fs::exists(out / "partial_2"));  // killed mid-run: left its partial marker
  EXPECT_FALSE(fs::exists(out / "task_2.txt"));

  const std::string again = cluster->sbatch(array_args("2", out, script));
  const auto redone = cluster->wait(again, seconds(60));
  ASSERT_EQ(redone.size(), 1u);
  EXPECT_EQ(redone.at(2), "COMPLETED");
  EXPECT_EQ(read_file(out / "task_2.txt"), again + " 2\n");
  EXPECT_FALSE(fs::exists(out / "partial_2"));
}

TEST_F(SlurmClusterTest, TwoClustersRunSideBySide) {
  std::string why_not;
  auto a = SlurmCluster::start(dir_ / "a", &why_not);
  if (!a) GTEST_SKIP() << why_not;
  auto b = SlurmCluster::start(dir_ / "b", &why_not);
  ASSERT_TRUE(b.has_value()) << why_not;
  EXPECT_NE(a->conf(), b->conf());

  const auto out_a = dir_ / "a" / "out";
  const auto out_b = dir_ / "b" / "out";
  const auto script = write_task_script(out_a);
  fs::create_directories(out_b);
  const std::string job_a = a->sbatch(array_args("0-1", out_a, script));
  const std::string job_b = b->sbatch("--array=0-1 --output=" + (out_b / "slurm-%A_%a.out").string() +
                                      " --wrap='echo $SLURM_ARRAY_TASK_ID > " + out_b.string() +
                                      "/task_$SLURM_ARRAY_TASK_ID.txt'");
  const auto states_a = a->wait(job_a, seconds(60));
  const auto states_b = b->wait(job_b, seconds(60));
  for (int task = 0; task < 2; ++task) {
    EXPECT_EQ(states_a.at(task), "COMPLETED");
    EXPECT_EQ(states_b.at(task), "COMPLETED");
    EXPECT_TRUE(fs::exists(out_a / ("task_" + std::to_string(task) + ".txt")));
    EXPECT_EQ(read_file(out_b / ("task_" + std::to_string(task) + ".txt")), std::to_string(task) + "\n");
  }
  // Each client reaches its own controller (both number their jobs from 1).
  EXPECT_NE(a->run("scontrol -o show job " + job_a).output.find("JobName=task.sh"), std::string::npos);
  EXPECT_NE(b->run("scontrol -o show job " + job_b).output.find("JobName=wrap"), std::string::npos);
}

}  // namespace
}  // namespace rcsim::testing
