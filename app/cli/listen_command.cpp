// rcsim listen: the reference client of `rcsim stream` (docs/stream.md).
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "cli/commands.hpp"
#include "cli/control_token.hpp"
#include "common/atomic_file.hpp"
#include "common/input_error.hpp"
#include "stream/endpoints.hpp"
#include "stream/listener.hpp"
#include "stream/streamer.hpp"

namespace rcsim::cli {
namespace {

struct ListenArgs {
  std::uint16_t port = 0;
  std::string bind;
  std::string group;
  std::string interface;
  std::string subscribe;
  std::string control_token_file;
  std::string messages;
  std::string sensors;
  std::string print = "simulated";
  std::string format = "csv";
  std::string output;
  std::string truth_output;
  std::string pcap;
  double idle_timeout_s = 0.0;
  bool keep_going = false;
};

std::uint32_t sensor_mask(const std::string& list) {
  std::uint32_t mask = 0;
  std::stringstream items(list);
  std::string item;
  while (std::getline(items, item, ',')) {
    std::size_t used = 0;
    int index = -1;
    try {
      index = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || index < 0 || index > 31) {
      throw InputError("--sensors", list, "expected sensor indices 0..31 separated by commas");
    }
    mask |= 1u << index;
  }
  return mask;
}

// The addresses and the control port are checked here, before any socket or file: a wrong one is
// bad input (exit status 2), named with its option, not a socket's "Invalid argument".
void check_address(const std::string& option, const std::string& text, bool multicast) {
  if (text.empty()) return;
  boost::system::error_code error;
  const auto address = boost::asio::ip::make_address(text, error);
  if (error) throw InputError(option, text, "not an IP address");
  if (multicast && !address.is_multicast()) throw InputError(option, text, "not a multicast group (224.0.0.0 to 239.255.255.255)");
}

void check_listen_arguments(const ListenArgs& args) {
  check_address("--bind", args.bind, false);
  check_address("--group", args.group, true);
  if (!args.group.empty() && !boost::asio::ip::make_address(args.group).is_v4()) {
    throw InputError("--group", args.group, "an IPv4 multicast group is joined (224.0.0.0 to 239.255.255.255)");
  }
  check_address("--interface", args.interface, false);
  if (args.subscribe.empty()) return;
  try {
    stream::parse_endpoint(args.subscribe, "127.0.0.1");
  } catch (const std::invalid_argument& e) {
    throw InputError("rcsim listen", "--subscribe", e.what());
  }
}

std::uint32_t listen_message_mask(const ListenArgs& args, stream::MessageType print) {
  if (args.messages.empty()) return stream::message_bit(print) | (args.truth_output.empty() ? 0u : stream::kTruthBit);
  try {
    return stream::parse_message_mask(args.messages);
  } catch (const std::invalid_argument& e) {
    throw InputError("rcsim listen", "--messages", e.what());
  }
}

// A --truth-output that stayed empty says why: a streamer sends ground truth only when asked.
void print_truth_hint(const ListenArgs& args, const stream::ListenSummary& summary) {
  if (args.truth_output.empty() || summary.truth_messages > 0) return;
  std::cerr << "rcsim listen: no ground truth arrived, so " << args.truth_output << " holds the header only: ";
  if (args.subscribe.empty()) {
    std::cerr << "a streamer sends it to its --to destinations only with --messages simulated,truth (or "
                 "recorded,truth), or subscribe at its control port with --subscribe\n";
  } else if (!args.messages.empty() && (listen_message_mask(args, stream::MessageType::simulated_targets) & stream::kTruthBit) == 0) {
    std::cerr << "--messages " << args.messages << " does not ask for it; add truth\n";
  } else {
    std::cerr << "the streamer sent none\n";
  }
}

void run_listen(const ListenArgs& args) {
  check_listen_arguments(args);
  stream::ListenOptions options;
  options.port = args.port;
  options.bind_address = args.bind;
  options.group = args.group;
  options.group_interface = args.interface;
  options.subscribe = args.subscribe;
  if (!args.control_token_file.empty()) options.control_token = read_control_token(args.control_token_file);
  options.print = args.print == "recorded" ? stream::MessageType::recorded_targets : stream::MessageType::simulated_targets;
  options.messages = listen_message_mask(args, options.print);
  options.sensor_mask = args.sensors.empty() ? 0u : sensor_mask(args.sensors);
  options.format = args.format == "jsonl" ? TargetListFormat::Jsonl : TargetListFormat::Csv;
  options.truth_output = args.truth_output;
  options.pcap_output = args.pcap;
  options.idle_timeout_s = args.idle_timeout_s;
  options.stop_at_end = !args.keep_going;
  options.handle_signals = true;

  // The capture is written as it arrives, so that a stop, an error or a full disk keeps what came
  // before; an output path that is a device or a link is refused first (docs/hardening.md).
  for (const std::string* path : {&args.output, &args.truth_output, &args.pcap}) {
    if (!path->empty() && *path != "-") check_output_file(*path);
  }
  std::optional<std::ofstream> file;
  if (!args.output.empty() && args.output != "-") {
    file.emplace(args.output, std::ios::binary | std::ios::trunc);
    if (!*file) throw InputError(args.output, "", std::string("cannot create the output: ") + std::strerror(errno));
  }
  std::ostream& out = file ? *file : std::cout;
  stream::Listener listener(options, out, std::cerr);
  stream::ListenSummary summary;
  try {
    summary = listener.run();
  } catch (const std::runtime_error& e) {
    if (file) {
      std::cerr << "rcsim listen: the target lists received before the error are in " << args.output << '\n';
      if (!*file) throw InputError(args.output, "", e.what());
    }
    throw;
  }
  std::cerr << summary.line() << std::endl;
  print_truth_hint(args, summary);
}

}  // namespace

void add_listen_command(CLI::App& app) {
  auto args = std::make_shared<ListenArgs>();
  auto* cmd = app.add_subcommand("listen", "receive an rcsim stream and print its target lists as rcsim simulate does");
  cmd->add_option("--port", args->port, "UDP port to receive on (0: any free port, printed at start)")->capture_default_str();
  cmd->add_option("--bind", args->bind, "Local address (default 127.0.0.1; 0.0.0.0 with --group)");
  cmd->add_option("--group", args->group, "Multicast group to join (IPv4)");
  cmd->add_option("--interface", args->interface, "IPv4 address of the interface to join the group on (e.g. 127.0.0.1)");
  cmd->add_option("--subscribe", args->subscribe, "Subscribe at a streamer's control port [HOST:]PORT instead of waiting passively");
  cmd->add_option("--control-token-file", args->control_token_file,
                  "With --subscribe: present the streamer's control token (a full streamer makes room for it)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--messages", args->messages, "What to subscribe to: simulated,recorded,truth (default: what is printed or written)");
  cmd->add_option("--sensors", args->sensors, "Subscribe to these sensor indices only, e.g. 0,1");
  cmd->add_option("--print", args->print, "Which target lists to print: simulated | recorded")
      ->check(CLI::IsMember({"simulated", "recorded"}))
      ->capture_default_str();
  cmd->add_option("--format", args->format, "csv | jsonl")->check(CLI::IsMember({"csv", "jsonl"}))->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output file, written as the target lists arrive; stdout if omitted");
  cmd->add_option("--truth-output", args->truth_output, "Write the ground truth (ego and object boxes) to this CSV file");
  cmd->add_option("--pcap", args->pcap, "Write every datagram received to this pcap file (for Wireshark/tshark)");
  cmd->add_option("--idle-timeout-s", args->idle_timeout_s, "End after this long without a datagram (0: never)")
      ->check(kNonNegative);
  cmd->add_flag("--keep-going", args->keep_going, "Do not end at the end-of-stream datagram");
  cmd->callback([args] { run_listen(*args); });
}

}  // namespace rcsim::cli
