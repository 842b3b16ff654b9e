#pragma once
// "HOST:PORT" and "[IPv6]:PORT" for the command line, resolved to UDP endpoints.
#include <boost/asio/ip/udp.hpp>
#include <string>

namespace rcsim::stream {

using boost::asio::ip::udp;

// HOST:PORT, [V6ADDR]:PORT, or (when default_host is given) just PORT. HOST may be a name;
// it is resolved once, IPv4 preferred. Throws std::invalid_argument naming the text.
udp::endpoint parse_endpoint(const std::string& text, const std::string& default_host = {});

std::string to_string(const udp::endpoint& endpoint);

}  // namespace rcsim::stream
