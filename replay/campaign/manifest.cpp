#include "replay/campaign/manifest.hpp"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "common/input_error.hpp"
#include "common/limits.hpp"
#include "common/safe_text.hpp"

namespace rcsim::replay::campaign {

namespace {

bool is_recording_dir(const std::filesystem::path& dir) {
  std::error_code ec;
  return std::filesystem::is_regular_file(dir / "recording.json", ec);
}

// The recording directories one entry names: a directory, or a glob(3) pattern (*, ?, [...]) of
// them. Relative entries are relative to the manifest's directory.
std::vector<std::filesystem::path> expand(const JsonField& entry, const std::filesystem::path& base_dir) {
  const std::string text = entry.json().is_string() ? entry.json().get<std::string>() : "";
  if (text.empty()) entry.fail("expected a non-empty path or pattern of recording directories");
  const std::filesystem::path pattern = std::filesystem::path(text).is_absolute() ? std::filesystem::path(text)
                                                                                   : base_dir / text;
  std::vector<std::filesystem::path> out;
  if (text.find_first_of("*?[") == std::string::npos) {
    if (!is_recording_dir(pattern)) entry.fail(fmt::format("'{}' is not a recording directory (no recording.json)", pattern.string()));
    out.push_back(pattern);
    return out;
  }
  glob_t matches{};
  const int status = ::glob(pattern.c_str(), GLOB_ERR, nullptr, &matches);
  if (status == 0) {
    for (std::size_t i = 0; i < matches.gl_pathc; ++i) {
      const std::filesystem::path match = matches.gl_pathv[i];
      if (is_recording_dir(match)) out.push_back(match);
    }
  }
  ::globfree(&matches);
  const std::string relative =
      std::filesystem::path(text).is_absolute() ? "" : fmt::format(" (a relative pattern is relative to the manifest's directory {})", base_dir.string());
  if (status == GLOB_ABORTED) {
    entry.fail(fmt::format("cannot expand '{}': a directory in it is missing or unreadable{}", pattern.string(), relative));
  }
  if (status != 0 && status != GLOB_NOMATCH) entry.fail(fmt::format("cannot expand '{}' (glob error {})", pattern.string(), status));
  if (out.empty()) entry.fail(fmt::format("'{}' matches no recording directory{}", pattern.string(), relative));
  return out;
}

}  // namespace

ReplayOptions CampaignReplay::options_for(const Recording& header) const {
  ReplayOptions out = options;
  out.fidelity = fidelity.value_or(default_fidelity_for(header));
  return out;
}

CampaignReplay parse_campaign_replay(const JsonField& r, const std::filesystem::path& base_dir) {
  r.expect_only({"seed", "fidelity", "store", "calibration", "sensor", "effects", "gospa_cutoff_m", "gospa_order",
                 "gate_m", "stationary_gate_mps", "smooth_half_window_s", "max_gap_s"});
  CampaignReplay out;
  ReplayOptions& o = out.options;
  if (r.has("seed")) {
    const double seed = r.number_within("seed", 0.0, 9007199254740992.0, "");  // 2^53: exact in JSON
    if (seed != std::floor(seed)) r.fail("seed", "expected a whole number");
    o.seed = static_cast<std::uint64_t>(seed);
  }
  if (r.has("fidelity")) {
    const std::string name = r.string("fidelity");
    out.fidelity = parse_fidelity(name);
    if (!out.fidelity) r.fail("fidelity", fmt::format("unknown fidelity level '{}'; one of {}", name, kFidelityNames));
  }
  if (r.has("store")) {
    const std::string store = r.string("store");
    if (store != "full" && store != "summary") r.fail("store", "'" + store + "' is neither full nor summary");
    out.store = store_level_from_name(store);
  }
  if (r.has("calibration")) {
    const std::filesystem::path dir = base_dir / r.string("calibration");
    if (!std::filesystem::is_directory(dir)) r.fail("calibration", "no such directory: " + dir.string());
    o.import.calibration_dir = std::filesystem::absolute(dir).lexically_normal().string();
  }
  if (r.has("sensor")) {
    // A built-in sensor's name, or a configuration file relative to the manifest.
    const std::string sensor = r.string("sensor");
    const bool is_path = sensor.find('/') != std::string::npos || sensor.ends_with(".json");
    o.import.sensor_type_override =
        is_path ? std::filesystem::absolute(base_dir / sensor).lexically_normal().string() : sensor;
  }
  if (r.has("effects")) {
    const JsonField e = r.member("effects");
    e.expect_only({"clutter", "multibounce", "occlusion"});
    o.import.effects = {e.boolean_or("clutter", false), e.boolean_or("multibounce", false),
                        e.boolean_or("occlusion", false)};
    o.import.effects_from_recording = false;
  }
  const auto positive = [&](const char* key, double fallback, double max) {
    if (!r.has(key)) return fallback;
    const double v = r.number_within(key, 0.0, max, "");
    if (v <= 0.0) r.fail(key, "expected a positive number");
    return v;
  };
  o.gospa.cutoff_m = positive("gospa_cutoff_m", o.gospa.cutoff_m, 1e4);
  o.gospa.order_p = positive("gospa_order", o.gospa.order_p, 100.0);
  if (o.gospa.order_p < 1.0) r.fail("gospa_order", "expected at least 1");
  o.association_gate_m = positive("gate_m", o.association_gate_m, 1e3);
  o.stationary_gate_mps = positive("stationary_gate_mps", o.stationary_gate_mps, 1e3);
  if (r.has("smooth_half_window_s")) o.import.smoothing_half_window_s = r.number_within("smooth_half_window_s", 0.0, 60.0, "s");
  o.import.max_gap_s = positive("max_gap_s", o.import.max_gap_s, 3600.0);
  return out;
}

CampaignManifest read_manifest(const std::filesystem::path& path) {
  CampaignManifest m;
  m.file = std::filesystem::absolute(path).lexically_normal();
  m.document = parse_json_file(path.string());
  const JsonField root(m.document, path.string(), "");
  root.expect_format("rcsim-campaign", 1);
  root.expect_only({"format", "version", "name", "description", "recordings", "replay", "criteria", "slurm"});
  m.name = root.string("name");
  // The name goes into the batch script, sbatch's job name, file names and commands printed to
  // be pasted: only a plain name is safe in all of them unquoted.
  if (!is_plain_name(m.name)) {
    root.fail("name", "expected a plain name: 1 to 64 letters, digits, '.', '_', '-' or '+', starting with a letter "
                      "or digit");
  }
  const std::filesystem::path base_dir = m.file.parent_path();
  for (const JsonField& entry : root.array("recordings")) {
    for (const auto& dir : expand(entry, base_dir)) {
      // A path goes into logs and status lines, one per recording.
      if (const auto bad = find_control_character(dir.string())) {
        entry.fail(fmt::format("the recording path '{}' holds {}: rename the folder", dir.string(), *bad));
      }
      m.recordings.push_back(std::filesystem::absolute(dir).lexically_normal());
    }
  }
  if (m.recordings.empty()) root.fail("recordings", "the campaign names no recording");
  std::sort(m.recordings.begin(), m.recordings.end());
  m.recordings.erase(std::unique(m.recordings.begin(), m.recordings.end()), m.recordings.end());
  if (root.has("replay")) m.replay = parse_campaign_replay(root.member("replay"), base_dir);
  if (root.has("criteria")) m.criteria = verdict::parse_criteria(root);
  if (root.has("slurm")) {
    const JsonField s = root.member("slurm");
    s.expect_only({"partition", "account", "time_limit", "memory", "extra"});
    const auto text = [&](const char* key) {
      if (!s.has(key)) return std::string();
      const std::string v = s.string(key);
      if (const auto bad = find_control_character(v)) s.fail(key, "must be one line of text; it holds " + *bad);
      return v;
    };
    m.slurm.partition = text("partition");
    m.slurm.account = text("account");
    m.slurm.time_limit = text("time_limit");
    m.slurm.memory = text("memory");
    if (s.has("extra")) {
      for (const JsonField& e : s.array("extra")) {
        const std::string v = e.json().is_string() ? e.json().get<std::string>() : "";
        if (!v.starts_with("--") || find_control_character(v)) {
          e.fail("expected one sbatch option on one line, starting with --");
        }
        m.slurm.extra.push_back(v);
      }
    }
  }
  return m;
}

}  // namespace rcsim::replay::campaign
