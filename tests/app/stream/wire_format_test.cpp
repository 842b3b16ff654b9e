// The rcsim-udp v1 encoder and decoder: exact round trips, datagram size limits, refusals by
// reason, and fuzzing with random, truncated, oversized and bit-flipped datagrams.
#include "stream/wire_format.hpp"

#include "stream/listener.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace rcsim::stream {
namespace {

TargetListMessage make_list(std::size_t n, std::string sensor = "front_left") {
  TargetListMessage m;
  m.cycle = 123456;
  m.sensor_index = 3;
  m.level = WireLevel::tracks;
  m.sensor_id = std::move(sensor);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = static_cast<double>(i);
    m.targets.push_back({static_cast<std::int32_t>(i) - 5, 1.5 + x * 0.25, -0.5 + x * 1e-3, -3.25 + x * 0.01, 10.0 - x * 0.125});
  }
  return m;
}

Bytes datagram_of(MessageType type, const Bytes& payload, std::uint16_t index = 0, std::uint16_t count = 1) {
  Header h;
  h.type = type;
  h.sequence = 42;
  h.timestamp_ns = 1'234'567'890'123;
  h.message_number = 7;
  h.fragment_index = index;
  h.fragment_count = count;
  return make_datagram(h, payload);
}

TEST(WireFormat, HeaderIsLittleEndianWithMagicAndVersion) {
  Header h;
  h.type = MessageType::ground_truth;
  h.flags = kFlagLate;
  h.sequence = 0x0102030405060708ULL;
  h.timestamp_ns = -2;
  h.message_number = 0xA1B2C3D4;
  h.fragment_index = 2;
  h.fragment_count = 5;
  std::array<std::uint8_t, kHeaderBytes> b{};
  encode_header(h, b.data());
  const std::array<std::uint8_t, kHeaderBytes> expected = {'R', 'C', 'S', 'M', 1, 0x03, 0x01, 0x00,           // magic..flags
                                                           8, 7, 6, 5, 4, 3, 2, 1,                       // sequence
                                                           0xFE, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,  // timestamp −2
                                                           0xD4, 0xC3, 0xB2, 0xA1, 2, 0, 5, 0};
  EXPECT_EQ(b, expected);
  const HeaderResult r = decode_header(b);
  ASSERT_EQ(r.error, DecodeError::none);
  EXPECT_EQ(r.header.sequence, h.sequence);
  EXPECT_EQ(r.header.timestamp_ns, -2);
  EXPECT_EQ(r.header.message_number, h.message_number);
  EXPECT_EQ(r.header.flags, kFlagLate);
}

TEST(WireFormat, TargetListRoundTripsExactlyInOneDatagram) {
  const TargetListMessage m = make_list(10);
  const auto payloads = encode_target_list(m);
  ASSERT_EQ(payloads.size(), 1u);
  EXPECT_EQ(payloads[0].size(), 20 + m.sensor_id.size() + 10 * kTargetBytes);
  TargetListFragment f;
  ASSERT_EQ(decode_target_list(payloads[0], f), DecodeError::none);
  EXPECT_EQ(f.total_count, 10u);
  EXPECT_EQ(f.first_index, 0u);
  EXPECT_EQ(f.message.cycle, m.cycle);
  EXPECT_EQ(f.message.sensor_index, 3);
  EXPECT_EQ(f.message.sensor_id, "front_left");
  ASSERT_EQ(f.message.targets.size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_EQ(f.message.targets[i].id, m.targets[i].id);
    // Bit-exact doubles: the listener prints what the simulation computed.
    EXPECT_EQ(f.message.targets[i].range_m, m.targets[i].range_m);
    EXPECT_EQ(f.message.targets[i].azimuth_rad, m.targets[i].azimuth_rad);
    EXPECT_EQ(f.message.targets[i].range_rate_mps, m.targets[i].range_rate_mps);
    EXPECT_EQ(f.message.targets[i].amplitude_db, m.targets[i].amplitude_db);
  }
}

TEST(WireFormat, LongListsSplitIntoFragmentsOfAtMost1472Bytes) {
  // (1472 − 32 − 20 − 10) / 36 = 39 targets per fragment for a 10-byte sensor id.
  const TargetListMessage m = make_list(100);
  const auto payloads = encode_target_list(m);
  ASSERT_EQ(payloads.size(), 3u);
  std::uint32_t next = 0;
  for (const Bytes& p : payloads) {
    EXPECT_LE(kHeaderBytes + p.size(), kMaxDatagramBytes);
    TargetListFragment f;
    ASSERT_EQ(decode_target_list(p, f), DecodeError::none);
    EXPECT_EQ(f.first_index, next);
    EXPECT_EQ(f.total_count, 100u);
    next += static_cast<std::uint32_t>(f.message.targets.size());
  }
  EXPECT_EQ(next, 100u);
  TargetListFragment first;
  ASSERT_EQ(decode_target_list(payloads[0], first), DecodeError::none);
  EXPECT_EQ(first.message.targets.size(), 39u);
  EXPECT_EQ(kHeaderBytes + payloads[0].size(), 32 + 20 + 10 + 39 * 36u);  // 1466
}

// Issue 49: a list of a sensor that measures elevation has flag bit 0 and 44-byte targets; a
// planar list keeps the 36-byte layout and a flags field of 0, byte for byte as before.
TEST(WireFormat, AListWithElevationCarriesItAsAFifthNumberPerTarget) {
  TargetListMessage m = make_list(2);
  const Bytes planar = encode_target_list(m).front();
  EXPECT_EQ(planar.size(), 20 + m.sensor_id.size() + 2 * 36);
  EXPECT_EQ(planar[18], 0);
  EXPECT_EQ(planar[19], 0);
  m.elevation = true;
  m.targets[0].elevation_rad = std::asin(0.1);
  m.targets[1].elevation_rad = -0.05;
  const Bytes elevated = encode_target_list(m).front();
  ASSERT_EQ(elevated.size(), 20 + m.sensor_id.size() + 2 * 44);
  EXPECT_EQ(elevated[18], 1);
  EXPECT_EQ(elevated[19], 0);
  // The first target's elevation: little-endian f64 at 20 + L + 36.
  double first_elevation_rad = 0.0;
  std::memcpy(&first_elevation_rad, elevated.data() + 20 + m.sensor_id.size() + 36, 8);
  EXPECT_EQ(first_elevation_rad, std::asin(0.1));
  // The rest of each target is where it was.
  EXPECT_TRUE(std::equal(planar.begin() + 20 + 10, planar.begin() + 20 + 10 + 36, elevated.begin() + 20 + 10));
  TargetListFragment f;
  ASSERT_EQ(decode_target_list(elevated, f), DecodeError::none);
  EXPECT_TRUE(f.message.elevation);
  ASSERT_EQ(f.message.targets.size(), 2u);
  EXPECT_EQ(f.message.targets[0].elevation_rad, std::asin(0.1));
  EXPECT_EQ(f.message.targets[1].elevation_rad, -0.05);
  EXPECT_EQ(f.message.targets[1].range_m, m.targets[1].range_m);
  ASSERT_EQ(decode_target_list(planar, f), DecodeError::none);
  EXPECT_FALSE(f.message.elevation);
  EXPECT_EQ(f.message.targets[0].elevation_rad, 0.0);
}

TEST(WireFormat, ElevationListsFragmentBy44BytesAndRefuseBadFlagsAndElevations) {
  // (1472 − 32 − 20 − 10) / 44 = 32 targets per fragment for a 10-byte sensor id.
  TargetListMessage m = make_list(100);
  m.elevation = true;
  const auto payloads = encode_target_list(m);
  ASSERT_EQ(payloads.size(), 4u);
  TargetListFragment f;
  ASSERT_EQ(decode_target_list(payloads[0], f), DecodeError::none);
  EXPECT_EQ(f.message.targets.size(), 32u);
  EXPECT_EQ(kHeaderBytes + payloads[0].size(), 32 + 20 + 10 + 32 * 44u);  // 1470
  Bytes p = encode_target_list(make_list(2)).front();
  p[18] = 2;  // an unknown flag
  EXPECT_EQ(decode_target_list(p, f), DecodeError::bad_value);
  p[18] = 1;  // the flag without the longer targets
  EXPECT_EQ(decode_target_list(p, f), DecodeError::bad_length);
  TargetListMessage steep = make_list(1);
  steep.elevation = true;
  steep.targets[0].elevation_rad = 1.58;
  EXPECT_EQ(decode_target_list(encode_target_list(steep).front(), f), DecodeError::none);
  steep.targets[0].elevation_rad = 1.6;
  EXPECT_EQ(decode_target_list(encode_target_list(steep).front(), f), DecodeError::bad_value);
  steep.targets[0].elevation_rad = std::nan("");
  EXPECT_EQ(decode_target_list(encode_target_list(steep).front(), f), DecodeError::bad_value);
}

// `rcsim listen` prints the elevation_rad column as `rcsim simulate` does for a 3D scene.
TEST(WireFormat, ListenRowsCarryTheElevationColumnWhenAsked) {
  TargetListMessage m = make_list(1);
  m.cycle = 2;
  m.elevation = true;
  m.targets[0] = {4, 10.0, 0.25, -1.5, 30.0, std::asin(0.1)};
  std::string csv, jsonl, planar;
  append_target_rows(csv, TargetListFormat::Csv, 80'000'000, m, true);
  append_target_rows(jsonl, TargetListFormat::Jsonl, 80'000'000, m, true);
  append_target_rows(planar, TargetListFormat::Csv, 80'000'000, m, false);
  EXPECT_EQ(target_rows_csv_header(true), "t_s,cycle,sensor,id,range_m,azimuth_rad,range_rate_mps,amplitude_db,elevation_rad\n");
  EXPECT_EQ(csv, "0.080000,2,front_left,4,10.0000,0.250000,-1.5000,30.000,0.100167\n");
  EXPECT_EQ(jsonl,
            "{\"t_s\":0.080000,\"cycle\":2,\"sensor\":\"front_left\",\"id\":4,\"range_m\":10.0000,\"azimuth_rad\":0.250000,"
            "\"range_rate_mps\":-1.5000,\"amplitude_db\":30.000,\"elevation_rad\":0.100167}\n");
  EXPECT_EQ(planar, "0.080000,2,front_left,4,10.0000,0.250000,-1.5000,30.000\n");
}

TEST(WireFormat, EmptyListIsOneFragmentWithNoTargets) {
  const auto payloads = encode_target_list(make_list(0));
  ASSERT_EQ(payloads.size(), 1u);
  TargetListFragment f;
  ASSERT_EQ(decode_target_list(payloads[0], f), DecodeError::none);
  EXPECT_EQ(f.total_count, 0u);
  EXPECT_TRUE(f.message.targets.empty());
}

TEST(WireFormat, GroundTruthRoundTripsAndFragmentsByObjectSize) {
  GroundTruthMessage m;
  m.cycle = 9;
  m.ego = {1.0, -2.0, 0.25, 13.5};
  for (std::uint32_t i = 0; i < 60; ++i) {
    m.objects.push_back({i * 2, {10.0 + i, -1.0, 3.0, 4.0}, 4.6, 1.8, fmt::format("object_{}", i)});
  }
  const auto payloads = encode_ground_truth(m);
  EXPECT_GT(payloads.size(), 1u);
  std::vector<WireObject> all;
  for (const Bytes& p : payloads) {
    EXPECT_LE(kHeaderBytes + p.size(), kMaxDatagramBytes);
    GroundTruthFragment f;
    ASSERT_EQ(decode_ground_truth(p, f), DecodeError::none);
    EXPECT_EQ(f.first_index, all.size());
    EXPECT_EQ(f.message.ego.speed_mps, 13.5);
    all.insert(all.end(), f.message.objects.begin(), f.message.objects.end());
  }
  ASSERT_EQ(all.size(), 60u);
  EXPECT_EQ(all[59].object_id, "object_59");
  EXPECT_EQ(all[59].object_index, 118u);
  EXPECT_EQ(all[59].pose.x_m, 69.0);
  EXPECT_EQ(all[59].length_m, 4.6);
}

TEST(WireFormat, EndReplyAndControlRoundTrip) {
  EndOfStream end{1000, 400, 100, 3}, end_back;
  ASSERT_EQ(decode_end_of_stream(encode_end_of_stream(end), end_back), DecodeError::none);
  EXPECT_EQ(end_back.datagrams_sent, 1000u);
  EXPECT_EQ(end_back.late_cycles, 3u);

  ControlReply reply;
  reply.request_sequence = 77;
  reply.request_type = MessageType::seek;
  reply.result = ReplyResult::out_of_range;
  reply.state = PlayState::paused;
  reply.next_cycle = 5;
  reply.control_ignored = 12;
  ControlReply back;
  ASSERT_EQ(decode_control_reply(encode_control_reply(reply), back), DecodeError::none);
  EXPECT_EQ(back.request_sequence, 77u);
  EXPECT_EQ(back.request_type, MessageType::seek);
  EXPECT_EQ(back.result, ReplyResult::out_of_range);
  EXPECT_EQ(back.state, PlayState::paused);
  EXPECT_EQ(back.control_ignored, 12u);

  ControlRequest request;
  ASSERT_EQ(decode_control_request(datagram_of(MessageType::subscribe, encode_control_payload(MessageType::subscribe, 5, 2)), request),
            DecodeError::none);
  EXPECT_EQ(request.argument, 5u);
  EXPECT_EQ(request.sensor_mask, 2u);
  ASSERT_EQ(decode_control_request(datagram_of(MessageType::seek, encode_control_payload(MessageType::seek, 99, 0)), request),
            DecodeError::none);
  EXPECT_EQ(request.argument, 99u);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::pause, {}), request), DecodeError::none);
}

TEST(WireFormat, RefusalsNameTheirReason) {
  const Bytes good = datagram_of(MessageType::pause, {});
  ControlRequest r;
  EXPECT_EQ(decode_control_request(std::span(good).first(31), r), DecodeError::too_short);
  EXPECT_EQ(decode_control_request(Bytes(1473, 0), r), DecodeError::too_long);
  Bytes bad = good;
  bad[0] = 'X';
  EXPECT_EQ(decode_control_request(bad, r), DecodeError::bad_magic);
  bad = good;
  bad[4] = 2;
  EXPECT_EQ(decode_control_request(bad, r), DecodeError::bad_version);
  bad = good;
  bad[5] = 0x7F;
  EXPECT_EQ(decode_control_request(bad, r), DecodeError::unknown_type);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::pause, {}, 1, 2), r), DecodeError::bad_fragment);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::pause, {0}), r), DecodeError::bad_length);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::step, encode_control_payload(MessageType::step, 0, 0)), r),
            DecodeError::bad_value);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::subscribe, encode_control_payload(MessageType::subscribe, 0x80, 0)), r),
            DecodeError::bad_value);
  EXPECT_EQ(decode_control_request(datagram_of(MessageType::simulated_targets, encode_target_list(make_list(1))[0]), r),
            DecodeError::wrong_kind);

  // A NaN in a target, a count beyond the total, a truncated target.
  TargetListMessage nan_list = make_list(2);
  nan_list.targets[1].range_m = std::numeric_limits<double>::quiet_NaN();
  TargetListFragment f;
  EXPECT_EQ(decode_target_list(encode_target_list(nan_list)[0], f), DecodeError::bad_value);
  Bytes payload = encode_target_list(make_list(2))[0];
  payload[8] = 1;  // total 1 < first 0 + 2 targets
  EXPECT_EQ(decode_target_list(payload, f), DecodeError::bad_value);
  payload = encode_target_list(make_list(2))[0];
  payload.pop_back();
  EXPECT_EQ(decode_target_list(payload, f), DecodeError::bad_length);
}

TEST(WireFormat, NumbersBeyondTheStatedLimitsAreRefusedAsFileReadersRefuseThem) {
  // schemas/limits.md: a range of 1e308 is no measurement (issue 21; the listener printed it
  // with all its digits, slowly). Each field just inside its limit decodes; just beyond, not.
  struct Case {
    double WireTarget::*field;
    double inside, beyond;
  };
  const std::vector<Case> cases = {{&WireTarget::range_m, 10'000.0, 10'000.5},
                                   {&WireTarget::range_m, -10'000.0, 1e308},
                                   {&WireTarget::azimuth_rad, -3.15, 3.16},
                                   {&WireTarget::azimuth_rad, 3.15, 90.0},
                                   {&WireTarget::range_rate_mps, -1000.0, -1000.5},
                                   {&WireTarget::amplitude_db, 1000.0, 1000.5}};
  TargetListFragment f;
  for (const Case& c : cases) {
    TargetListMessage list = make_list(2);
    list.targets[1].*c.field = c.inside;
    EXPECT_EQ(decode_target_list(encode_target_list(list)[0], f), DecodeError::none) << c.inside;
    list.targets[1].*c.field = c.beyond;
    EXPECT_EQ(decode_target_list(encode_target_list(list)[0], f), DecodeError::bad_value) << c.beyond;
  }
  GroundTruthFragment g;
  GroundTruthMessage truth;
  truth.objects.push_back({0, {1.0, 2.0, 0.0, 0.0}, 4.0, 2.0, "car"});
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::none);
  truth.objects[0].length_m = 100.5;
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::bad_value);
  truth.objects[0].length_m = 4.0;
  truth.ego.x_m = 2e7;
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::bad_value);
  truth.ego.x_m = 0.0;
  truth.objects[0].pose.speed_mps = 1e4;
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::bad_value);
}

TEST(WireFormat, IdsMustBeWellFormedUtf8) {
  // A sensor id of one byte 0xFF ended `rcsim listen --format jsonl` (the JSON writer threw on
  // it); found with the fuzz harness's path (tests/fuzz/regressions/udp_datagram/).
  TargetListFragment f;
  const std::vector<std::string> good = {"front_left", "Radar vorne \xC3\xA4", "\xE9\x9B\xB7\xE8\xBE\xBE",
                                        "\xF0\x9F\x9A\x97", "\xF4\x8F\xBF\xBF", std::string(1, '\0')};
  const std::vector<std::string> bad = {"\xFF", "\xC0\xAF", "\xC3", "\xE2\x82", "\xED\xA0\x80", "\xF4\x90\x80\x80", "ok\x80",
                                        "\xF5\x80\x80\x80", "\xE0\x80\xAF"};
  for (const std::string& id : good) {
    EXPECT_EQ(decode_target_list(encode_target_list(make_list(1, id))[0], f), DecodeError::none) << id;
  }
  for (const std::string& id : bad) {
    EXPECT_EQ(decode_target_list(encode_target_list(make_list(1, id))[0], f), DecodeError::bad_value) << id;
  }
  GroundTruthMessage truth;
  truth.objects.push_back({0, {1.0, 2.0, 0.0, 0.0}, 4.0, 2.0, "car\xFF"});
  GroundTruthFragment g;
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::bad_value);
  truth.objects[0].object_id = "car_\xC3\xA4";
  EXPECT_EQ(decode_ground_truth(encode_ground_truth(truth)[0], g), DecodeError::none);
}

TEST(WireFormat, FuzzedControlDatagramsNeverCrashAndAreAllCounted) {
  std::mt19937_64 rng(20240601);
  std::array<std::uint64_t, kDecodeErrorCount> counts{};
  const std::vector<Bytes> valid = {
      datagram_of(MessageType::subscribe, encode_control_payload(MessageType::subscribe, 7, 0)),
      datagram_of(MessageType::step, encode_control_payload(MessageType::step, 3, 0)),
      datagram_of(MessageType::seek, encode_control_payload(MessageType::seek, 3, 0)),
      datagram_of(MessageType::keepalive, {}),
  };
  constexpr int kCases = 60000;
  for (int i = 0; i < kCases; ++i) {
    Bytes d;
    switch (i % 4) {
      case 0: {  // random bytes of random length, up to well over the limit
        d.resize(std::uniform_int_distribution<std::size_t>(0, 3000)(rng));
        for (auto& b : d) b = static_cast<std::uint8_t>(rng());
        break;
      }
      case 1: {  // a valid request truncated or extended
        d = valid[rng() % valid.size()];
        d.resize(std::uniform_int_distribution<std::size_t>(0, d.size() + 16)(rng), 0xAB);
        break;
      }
      case 2: {  // a valid request with a few bits flipped
        d = valid[rng() % valid.size()];
        for (int k = 0; k < 3; ++k) d[rng() % d.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        break;
      }
      default: {  // the magic and version right, the rest random
        d.resize(std::uniform_int_distribution<std::size_t>(32, 48)(rng));
        for (auto& b : d) b = static_cast<std::uint8_t>(rng());
        std::copy(kMagic.begin(), kMagic.end(), d.begin());
        d[4] = kWireVersion;
        break;
      }
    }
    ControlRequest r;
    ++counts[static_cast<std::size_t>(decode_control_request(d, r))];
    // Every datagram also goes through the data decoders without harm.
    const HeaderResult h = decode_header(d);
    if (h.error == DecodeError::none) {
      const auto payload = std::span<const std::uint8_t>(d).subspan(kHeaderBytes);
      TargetListFragment tl;
      GroundTruthFragment gt;
      EndOfStream end;
      ControlReply reply;
      decode_target_list(payload, tl);
      decode_ground_truth(payload, gt);
      decode_end_of_stream(payload, end);
      decode_control_reply(payload, reply);
    }
  }
  std::uint64_t total = 0;
  for (auto c : counts) total += c;
  EXPECT_EQ(total, static_cast<std::uint64_t>(kCases));
  for (DecodeError e : {DecodeError::too_short, DecodeError::too_long, DecodeError::bad_magic, DecodeError::bad_length,
                        DecodeError::unknown_type}) {
    EXPECT_GT(counts[static_cast<std::size_t>(e)], 0u) << decode_error_name(e);
  }
  // Some flipped bits land in the sequence or timestamp and leave a valid request.
  EXPECT_GT(counts[0], 0u);
  EXPECT_LT(counts[0], static_cast<std::uint64_t>(kCases) / 4);
}

TEST(WireFormat, FuzzedDataPayloadsDecodeOrRefuseWithoutCrashing) {
  std::mt19937_64 rng(7);
  GroundTruthMessage gt;
  gt.ego = {1, 2, 3, 4};
  for (std::uint32_t i = 0; i < 5; ++i) gt.objects.push_back({i, {1, 2, 3, 4}, 4, 2, fmt::format("o{}", i)});
  const std::vector<Bytes> seeds = {encode_target_list(make_list(12))[0], encode_ground_truth(gt)[0]};
  int refused = 0;
  for (int i = 0; i < 40000; ++i) {
    Bytes p = seeds[static_cast<std::size_t>(i) % 2];
    if (i % 3 == 0) p.resize(rng() % (p.size() + 1));
    for (int k = 0; k < 2; ++k) {
      if (!p.empty()) p[rng() % p.size()] = static_cast<std::uint8_t>(rng());
    }
    TargetListFragment tl;
    GroundTruthFragment g;
    const DecodeError e = i % 2 == 0 ? decode_target_list(p, tl) : decode_ground_truth(p, g);
    if (e != DecodeError::none) {
      ++refused;
    } else if (i % 2 == 0) {
      EXPECT_LE(tl.first_index + tl.message.targets.size(), tl.total_count);
    }
  }
  EXPECT_GT(refused, 10000);
}

}  // namespace
}  // namespace rcsim::stream
