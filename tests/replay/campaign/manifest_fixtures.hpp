#pragma once
// A campaign manifest written from its body (the fields after "format", "version", "name"), and
// what reading it refused: for the manifest's and the plan's tests.
#include <filesystem>
#include <fstream>
#include <string>

#include "common/input_error.hpp"
#include "replay/campaign/manifest.hpp"
#include "scratch_dir.hpp"

namespace rcsim::testing {

class ManifestFileTest : public ScratchDirTest {
 protected:
  explicit ManifestFileTest(std::string tag) : ScratchDirTest(std::move(tag)) {}
  std::filesystem::path write_manifest(const std::string& body) {
    const auto path = dir_ / "campaign.json";
    std::ofstream(path) << R"({"format": "rcsim-campaign", "version": 1, "name": "t", )" << body << "}";
    return path;
  }
  // The refusal's message, or "no error".
  std::string error_of(const std::string& body) {
    try {
      replay::campaign::read_manifest(write_manifest(body));
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
};

}  // namespace rcsim::testing
