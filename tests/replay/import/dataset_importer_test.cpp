// The dataset importers' registry and the --frames list (replay/import/dataset_importer.hpp):
// lists parsed item by item by hand, and every malformed one refused naming --frames.
#include "replay/import/dataset_importer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/input_error.hpp"

namespace rcsim::replay::dataset_importer_test {

// The ranges as "first-last" pairs, for one comparison.
std::vector<std::pair<long long, long long>> pairs_of(const std::vector<FrameRange>& ranges) {
  std::vector<std::pair<long long, long long>> out;
  for (const FrameRange& r : ranges) out.emplace_back(r.first, r.last);
  return out;
}

// The refusal's text and where it points; "" where nothing is refused.
std::string refusal_of(const std::string& list) {
  try {
    parse_frame_list(list);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--frames") << list;
    return e.what();
  }
  return "";
}

TEST(DatasetImporter, FrameListsParseAsWrittenInOrder) {
  using Pairs = std::vector<std::pair<long long, long long>>;
  EXPECT_EQ(pairs_of(parse_frame_list("0-199")), (Pairs{{0, 199}}));
  EXPECT_EQ(pairs_of(parse_frame_list("0,4")), (Pairs{{0, 0}, {4, 4}}));
  EXPECT_EQ(pairs_of(parse_frame_list("0-9,20")), (Pairs{{0, 9}, {20, 20}}));
  // Kept as written: not sorted, not merged, a one-frame range as it is; overlaps are the importer's to refuse.
  EXPECT_EQ(pairs_of(parse_frame_list("7,3-3,0-5")), (Pairs{{7, 7}, {3, 3}, {0, 5}}));
  // The largest frame number allowed, 10^9.
  EXPECT_EQ(pairs_of(parse_frame_list("1000000000")), (Pairs{{1000000000, 1000000000}}));
}

TEST(DatasetImporter, MalformedFrameListsAreRefusedNamingTheItem) {
  EXPECT_EQ(refusal_of(""), "--frames: an empty list (give frames such as 0-199 or 0,4; without --frames, all)");
  EXPECT_EQ(refusal_of("1000000001"),
            "--frames: '1000000001' in '1000000001' is not a frame number (whole numbers 0 to 1000000000; a list such "
            "as 0-199 or 0-9,20)");
  EXPECT_EQ(refusal_of("9-4"), "--frames: '9-4' in '9-4' runs backwards (write 4-9)");
  // The offending item, each: a trailing comma leaves an empty one; a sign, a space, a second dash,
  // a decimal point are no part of a whole number.
  for (const auto& [list, item] : std::vector<std::pair<std::string, std::string>>{
           {"1,", "''"}, {"-1", "''"}, {"+1", "'+1'"}, {" 1", "' 1'"}, {"1-2-3", "'2-3'"}, {"2.5", "'2.5'"}, {"0-x", "'x'"}}) {
    const std::string message = refusal_of(list);
    EXPECT_EQ(message.rfind("--frames: " + item + " in '" + list + "' is not a frame number", 0), 0u) << list << ": " << message;
  }
}

TEST(DatasetImporter, ImportersAreFoundByNameAndAnUnknownOneListsTheKnown) {
  ASSERT_EQ(dataset_importers().size(), 5u);
  EXPECT_EQ(&find_dataset_importer("astyx"), &dataset_importers()[1]);
  EXPECT_EQ(find_dataset_importer("aimotive").name, "aimotive");
  EXPECT_EQ(find_dataset_importer("mcap").name, "mcap");
  EXPECT_EQ(find_dataset_importer("vod").name, "vod");
  EXPECT_EQ(find_dataset_importer("rosbag2").import_to, find_dataset_importer("mcap").import_to);  // one importer, two names
  for (const DatasetImporter& importer : dataset_importers()) {
    EXPECT_NE(importer.import, nullptr) << importer.name;
    EXPECT_FALSE(importer.description.empty()) << importer.name;
  }
  try {
    find_dataset_importer("Astyx");  // names are case-sensitive
    ADD_FAILURE() << "an unknown dataset was found";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "--from");
    EXPECT_STREQ(e.what(), "--from: unknown dataset 'Astyx' (known: aimotive, astyx, mcap, rosbag2, vod)");
  }
}

}  // namespace rcsim::replay::dataset_importer_test
