#include "replay/verdict/junit.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/chrono.h>
#include <fmt/format.h>

#include "common/atomic_file.hpp"
#include "common/xml_escape.hpp"

namespace rcsim::replay::verdict {

std::string junit_xml(const Verdicts& v, const std::string& suite) {
  const std::size_t campaign_failed =
      static_cast<std::size_t>(std::count_if(v.campaign.begin(), v.campaign.end(), [](const auto& r) { return !r.passed; }));
  const std::size_t tests = v.runs.size() + v.campaign.size();
  const std::size_t failures = static_cast<std::size_t>(v.runs_failed) + campaign_failed;
  double time_s = 0.0;
  for (const RunVerdict& r : v.runs) time_s += r.wall_s;
  const std::string timestamp =
      fmt::format("{:%Y-%m-%dT%H:%M:%S}", fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
  const std::string name = xml_escape(suite);

  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += fmt::format("<testsuites name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" time=\"{:.3f}\">\n", name, tests,
                   failures, time_s);
  x += fmt::format("  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"0\" time=\"{:.3f}\" "
                   "timestamp=\"{}\">\n",
                   name, tests, failures, time_s, timestamp);
  x += "    <properties>\n";
  for (std::size_t i = 0; i < v.criteria.size(); ++i) {
    x += fmt::format("      <property name=\"criterion.{}\" value=\"{}\"/>\n", i, xml_escape(v.criteria[i].text()));
  }
  x += "    </properties>\n";
  for (const RunVerdict& r : v.runs) {
    x += fmt::format("    <testcase classname=\"{}\" name=\"{}\" time=\"{:.3f}\"", name,
                     xml_escape(fmt::format("{} (seed {}, run {})", r.recording_name, r.seed, r.run_id)), r.wall_s);
    if (r.passed) {
      x += "/>\n";
      continue;
    }
    std::string first, all;
    for (const CriterionResult& c : r.results) {
      if (c.passed) continue;
      const std::string line = describe_failure(v.criteria[c.criterion], c);
      if (first.empty()) first = line;
      all += line + "\n";
    }
    x += ">\n";
    x += fmt::format("      <failure message=\"{}\" type=\"criterion\">{}recording: {}</failure>\n", xml_escape(first),
                     xml_escape(all), xml_escape(r.recording_dir));
    x += "    </testcase>\n";
  }
  for (const CriterionResult& c : v.campaign) {
    const Criterion& criterion = v.criteria[c.criterion];
    x += fmt::format("    <testcase classname=\"{}.campaign\" name=\"{}\" time=\"0\"", name, xml_escape(criterion.text()));
    if (c.passed) {
      x += "/>\n";
      continue;
    }
    const std::string line = describe_failure(criterion, c);
    x += fmt::format(">\n      <failure message=\"{}\" type=\"criterion\">{}</failure>\n    </testcase>\n",
                     xml_escape(line), xml_escape(line));
  }
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

void write_junit(const std::string& path, const Verdicts& verdicts, const std::string& suite) {
  AtomicFileWriter out(path);
  out.stream() << junit_xml(verdicts, suite);
  out.commit();
}

}  // namespace rcsim::replay::verdict
