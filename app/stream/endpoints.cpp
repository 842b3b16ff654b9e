#include "stream/endpoints.hpp"

#include <fmt/format.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>
#include <charconv>
#include <stdexcept>

namespace rcsim::stream {

udp::endpoint parse_endpoint(const std::string& text, const std::string& default_host) {
  const auto fail = [&text](const std::string& why) {
    return std::invalid_argument(fmt::format("'{}': {} (expected HOST:PORT)", text, why));
  };
  std::string host, port_text;
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) {
    if (default_host.empty()) throw fail("no port");
    host = default_host;
    port_text = text;
  } else {
    host = text.substr(0, colon);
    port_text = text.substr(colon + 1);
    if (host.size() >= 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    if (host.empty()) host = default_host.empty() ? "127.0.0.1" : default_host;
  }
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (ec != std::errc() || end != port_text.data() + port_text.size() || port > 65535) throw fail("bad port");
  boost::system::error_code error;
  const auto address = boost::asio::ip::make_address(host, error);
  if (!error) return {address, static_cast<unsigned short>(port)};
  boost::asio::io_context io;
  udp::resolver resolver(io);
  const auto results = resolver.resolve(host, port_text, error);
  if (error || results.empty()) throw fail(fmt::format("cannot resolve host '{}'", host));
  for (const auto& r : results) {
    if (r.endpoint().address().is_v4()) return r.endpoint();
  }
  return results.begin()->endpoint();
}

std::string to_string(const udp::endpoint& endpoint) {
  const auto address = endpoint.address();
  if (address.is_v6()) return fmt::format("[{}]:{}", address.to_string(), endpoint.port());
  return fmt::format("{}:{}", address.to_string(), endpoint.port());
}

}  // namespace rcsim::stream
