#pragma once
// SIGINT and SIGTERM end a stream or a capture cleanly: the streamer and the listener both wait
// for them on their io_context and then stop as if asked to, marking the summary interrupted.
#include <boost/asio/signal_set.hpp>
#include <csignal>
#include <functional>

namespace rcsim::stream {

// Adds SIGINT and SIGTERM to `signals` and calls `on_stop` once, on the first of them (not when
// the wait is cancelled).
inline void stop_on_signals(boost::asio::signal_set& signals, std::function<void()> on_stop) {
  signals.add(SIGINT);
  signals.add(SIGTERM);
  signals.async_wait([on_stop = std::move(on_stop)](const boost::system::error_code& ec, int) {
    if (!ec) on_stop();
  });
}

}  // namespace rcsim::stream
