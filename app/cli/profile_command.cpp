// rcsim profile derive: a sensor profile read off real recordings (docs/profile-derive.md).
#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.hpp"
#include "cli/seed_option.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "io/recording.hpp"
#include "replay/profile/profile_derivation.hpp"
#include "replay/report/profile_report.hpp"

namespace rcsim::cli {
namespace {

struct DeriveArgs {
  std::vector<std::string> recordings;
  std::string output, base, name, report;
  bool json = false;
};

void print_derivation(const replay::profile::ProfileDerivation& d, const std::string& output) {
  std::cout << fmt::format("rcsim profile derive: {} detections in {} sensor cycles; base {}\n\n", d.detections, d.sensor_cycles, d.base);
  for (const auto& v : d.values) {
    // field, value, source (derived, derived weak, recording, base), the interval from the evidence, the evidence
    std::cout << fmt::format("{:<52} {:>16}  {:<13} {:<22} {}{}\n", v.field, replay::profile::value_text(v.value),
                             replay::profile::source_text(v), replay::profile::interval_text(v), v.evidence,
                             v.support > 0 ? fmt::format(" [{}]", v.support) : "");
  }
  std::cout << fmt::format("\n{0}: written. Fit what the data cannot show (the base's values) with rcsim calibrate RECORDING "
                           "--real-drive --sensor {0} -o FIT, then replay with rcsim replay RECORDING --sensor {0} "
                           "--calibration FIT\n",
                           output);
}

void run_derive(const DeriveArgs& args) {
  check_output_file(args.output);
  if (!args.report.empty()) check_output_file(args.report);
  std::vector<Recording> recordings;
  for (const std::string& dir : args.recordings) recordings.push_back(read_recording(dir));
  std::vector<const Recording*> pointers;
  for (const Recording& r : recordings) pointers.push_back(&r);
  replay::profile::DeriveOptions options;
  options.base = args.base;
  options.name = args.name.empty() ? std::filesystem::path(args.output).stem().string() : args.name;
  const replay::profile::ProfileDerivation d = replay::profile::derive_profile(pointers, options);
  AtomicFileWriter file(args.output);
  file.stream() << d.profile.dump(2) << '\n';
  file.commit();
  if (!args.report.empty()) {
    AtomicFileWriter page(args.report);
    replay::write_profile_report(page.stream(), d, args.output);
    page.commit();
  }
  if (!args.json) return print_derivation(d, args.output);
  nlohmann::ordered_json values = nlohmann::ordered_json::array();
  for (const auto& v : d.values) {
    nlohmann::ordered_json value{{"field", v.field}, {"value", v.value}, {"source", replay::profile::value_source_name(v.source)},
                                 {"weak", v.weak}};
    value["interval"] = v.has_interval() ? nlohmann::ordered_json::array({v.low, v.high}) : nlohmann::ordered_json();
    value["evidence"] = v.evidence;
    value["support"] = v.support;
    values.push_back(std::move(value));
  }
  std::cout << nlohmann::ordered_json{{"profile", args.output}, {"base", d.base}, {"detections", d.detections}, {"values", values}}.dump(2) << '\n';
}

}  // namespace

void add_profile_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("profile", "sensor profiles from real recordings (derive)");
  cmd->require_subcommand(1);
  auto args = std::make_shared<DeriveArgs>();
  auto* derive = cmd->add_subcommand("derive", "derive a sensor profile (rcsim-sensor) from recordings of raw detections");
  derive->add_option("recordings", args->recordings, "Recording directories of one kind of radar")->required();
  derive->add_option("-o,--output", args->output, "The profile to write (atomically)")->required();
  derive->add_option("--base", args->base,
                     "Profile for what the data cannot show: a built-in name or an rcsim-sensor file (default: the recordings' sensor type)");
  derive->add_option("--name", args->name, "The profile's name (default: the output file's stem)");
  derive->add_flag("--json", args->json, "Print each value with its evidence as JSON");
  derive->add_option("--report", args->report, "Also write an HTML page with every value and the fits it was read from");
  derive->callback([args] { run_derive(*args); });
}

}  // namespace rcsim::cli
