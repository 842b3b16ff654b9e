#pragma once
// A fresh directory for one test under the system's temporary directory, removed afterwards:
// named after the process and the test, so tests running in parallel never share one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

namespace rcsim::testing {

inline std::filesystem::path fresh_scratch_dir(const std::string& tag) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string name = test != nullptr ? std::string("_") + test->name() : std::string();
  const auto dir = std::filesystem::temp_directory_path() / ("rcsim_" + tag + "_" + std::to_string(::getpid()) + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A file's bytes as they are ("" where it cannot be read).
inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Fixture base: dir_ is fresh in every test.
class ScratchDirTest : public ::testing::Test {
 protected:
  explicit ScratchDirTest(std::string tag) : tag_(std::move(tag)) {}
  void SetUp() override { dir_ = fresh_scratch_dir(tag_); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // `bytes` as the file dir_/name, exactly (binary, replacing any earlier one).
  std::filesystem::path write_file(const std::string& name, const std::string& bytes) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
    return path;
  }
  std::filesystem::path dir_;

 private:
  std::string tag_;
};

}  // namespace rcsim::testing
