#pragma once
// Verdicts as JUnit XML, the test report CI systems display (Jenkins, GitLab, GitHub actions):
// one <testcase> per run, failed with one <failure> listing its failed criteria, and one per
// campaign criterion (schemas/campaign.md, "JUnit"). Validated against tests/end_to_end/junit.xsd,
// which follows the schema Jenkins' xUnit plugin reads (junit-10.xsd).
#include <string>

#include "replay/verdict/criteria.hpp"

namespace rcsim::replay::verdict {

// The XML text; `suite` names the test suite (the campaign, or the report's file name).
std::string junit_xml(const Verdicts& verdicts, const std::string& suite);

// Writes it atomically.
void write_junit(const std::string& path, const Verdicts& verdicts, const std::string& suite);

}  // namespace rcsim::replay::verdict
