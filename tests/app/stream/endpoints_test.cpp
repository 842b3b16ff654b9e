// parse_endpoint and to_string of app/stream/endpoints.hpp: IPv4, bracketed IPv6, a bare port
// with a default host, a name from the hosts file, and the texts refused (the message quotes them).
#include "stream/endpoints.hpp"

#include <gtest/gtest.h>

#include <boost/asio/ip/address.hpp>
#include <stdexcept>
#include <string>

namespace rcsim::endpoints_test {

using stream::parse_endpoint;
using stream::udp;

// The message of the std::invalid_argument parse_endpoint throws, or "" when it accepts.
std::string refusal(const std::string& text, const std::string& default_host = {}) {
  try {
    (void)parse_endpoint(text, default_host);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(StreamEndpoints, ParsesAddressesPortsAndDefaults) {
  const udp::endpoint v4 = parse_endpoint("10.1.2.3:5000");
  EXPECT_TRUE(v4.address().is_v4());
  EXPECT_EQ(v4.address().to_string(), "10.1.2.3");
  EXPECT_EQ(v4.port(), 5000);
  const udp::endpoint v6 = parse_endpoint("[::1]:6000");
  EXPECT_TRUE(v6.address().is_v6());
  EXPECT_EQ(v6.address().to_string(), "::1");
  EXPECT_EQ(v6.port(), 6000);
  // The last colon separates the port: unbracketed "::1:6001" is ::1, port 6001.
  EXPECT_EQ(parse_endpoint("::1:6001"), udp::endpoint(boost::asio::ip::make_address("::1"), 6001));
  // A bare port takes the default host; an empty host takes it too, or 127.0.0.1 without one.
  EXPECT_EQ(parse_endpoint("7000", "0.0.0.0"), udp::endpoint(boost::asio::ip::make_address("0.0.0.0"), 7000));
  EXPECT_EQ(parse_endpoint(":7001"), udp::endpoint(boost::asio::ip::make_address("127.0.0.1"), 7001));
  EXPECT_EQ(parse_endpoint(":7002", "0.0.0.0").address().to_string(), "0.0.0.0");
  // The port range's ends.
  EXPECT_EQ(parse_endpoint("127.0.0.1:0").port(), 0);
  EXPECT_EQ(parse_endpoint("127.0.0.1:65535").port(), 65535);
  // A name is resolved (from the hosts file), IPv4 preferred.
  const udp::endpoint named = parse_endpoint("localhost:9000");
  EXPECT_TRUE(named.address().is_v4());
  EXPECT_TRUE(named.address().is_loopback());
  EXPECT_EQ(named.port(), 9000);
}

TEST(StreamEndpoints, RefusesTextsWithoutAGoodPortQuotingThem) {
  EXPECT_EQ(refusal("5000"), "'5000': no port (expected HOST:PORT)");
  EXPECT_EQ(refusal("127.0.0.1:65536"), "'127.0.0.1:65536': bad port (expected HOST:PORT)");
  EXPECT_EQ(refusal("127.0.0.1:"), "'127.0.0.1:': bad port (expected HOST:PORT)");
  EXPECT_EQ(refusal("127.0.0.1:-1"), "'127.0.0.1:-1': bad port (expected HOST:PORT)");
  EXPECT_EQ(refusal("127.0.0.1:80x"), "'127.0.0.1:80x': bad port (expected HOST:PORT)");
  EXPECT_EQ(refusal("127.0.0.1: 80"), "'127.0.0.1: 80': bad port (expected HOST:PORT)");
  // Brackets without a port: the last colon is inside them, "1]" is no port.
  EXPECT_EQ(refusal("[::1]"), "'[::1]': bad port (expected HOST:PORT)");
  // With a default host a bad bare port is a bad port, not a missing one.
  EXPECT_EQ(refusal("http", "0.0.0.0"), "'http': bad port (expected HOST:PORT)");
}

TEST(StreamEndpoints, ToStringBracketsIPv6AndRoundTrips) {
  EXPECT_EQ(stream::to_string(udp::endpoint(boost::asio::ip::make_address("10.0.0.1"), 53)), "10.0.0.1:53");
  EXPECT_EQ(stream::to_string(udp::endpoint(boost::asio::ip::make_address("::1"), 6000)), "[::1]:6000");
  EXPECT_EQ(stream::to_string(udp::endpoint(boost::asio::ip::make_address("fe80::2"), 1)), "[fe80::2]:1");
  for (const std::string text : {"192.168.0.7:4000", "[2001:db8::5]:123", "0.0.0.0:0"}) {
    EXPECT_EQ(stream::to_string(parse_endpoint(text)), text);
  }
}

}  // namespace rcsim::endpoints_test
