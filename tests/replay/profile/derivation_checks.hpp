#pragma once
// The values of a derived profile by field, and the check the derivation tests share: a value
// derived (not the base's) within a tolerance of what it should be.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "replay/profile/derived_value.hpp"

namespace rcsim::testing {

inline std::map<std::string, replay::profile::DerivedValue> by_field(const std::vector<replay::profile::DerivedValue>& values) {
  std::map<std::string, replay::profile::DerivedValue> out;
  for (const replay::profile::DerivedValue& v : values) out[v.field] = v;
  return out;
}

// The value of `field`, derived, within `tolerance` of `truth` (a hand profile's or the one that
// made the data).
inline void expect_derived_near(const std::map<std::string, replay::profile::DerivedValue>& values, const std::string& field, double truth,
                                double tolerance) {
  const auto it = values.find(field);
  ASSERT_NE(it, values.end()) << field;
  EXPECT_EQ(it->second.source, replay::profile::ValueSource::derived) << field << ": " << it->second.evidence;
  EXPECT_NEAR(it->second.value.get<double>(), truth, tolerance) << field << ": " << it->second.evidence;
}

}  // namespace rcsim::testing
