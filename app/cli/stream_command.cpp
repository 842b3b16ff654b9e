// rcsim stream SCENE.json|RECORDING_DIR: live UDP playback (docs/stream.md, schemas/udp-stream.md).
#include <boost/asio/ip/address_v4.hpp>
#include <boost/system/error_code.hpp>
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>

#include "cli/commands.hpp"
#include "cli/control_token.hpp"
#include "cli/fidelity_option.hpp"
#include "cli/seed_option.hpp"
#include "common/input_error.hpp"
#include "stream/streamer.hpp"

namespace rcsim::cli {
namespace {

struct StreamArgs {
  std::string input;
  std::vector<std::string> to;
  std::string control;
  std::string control_token_file;
  bool open_control = false;
  std::string speed = "1";
  bool stepped = false;
  std::string messages;
  std::string level = "tracks";
  std::uint64_t seed = kDefaultSeed;
  bool no_noise = false;
  std::string fidelity = "full";
  int wait_clients = 0;
  double client_timeout_s = 5.0;
  std::size_t max_clients = 16;
  double late_ms = 2.0;
  int ttl = 1;
  std::string multicast_interface;
  int from_cycle = 0;
  bool hold = false;
  std::size_t queue_cycles = 64;
  int realtime = 0;
};

// The streamer's own checks of the command line (speed, message types, destinations, control
// port) throw std::invalid_argument: bad input, exit status 2 (README, "Exit status").
template <typename Parse>
auto parsed_or_input_error(const std::string& option, Parse parse) {
  try {
    return parse();
  } catch (const std::invalid_argument& e) {
    throw InputError("rcsim stream", option, e.what());
  }
}

void run_stream(const StreamArgs& args) {
  stream::SourceOptions source_options;
  source_options.simulation.level = args.level == "detections" ? ListLevel::detections : ListLevel::tracks;
  source_options.simulation.seed = args.seed;
  source_options.simulation.noise = !args.no_noise;
  source_options.simulation.fidelity = fidelity_from_arg(args.fidelity);
  const auto source = stream::open_source(args.input, source_options);

  stream::StreamOptions options;
  options.destinations = args.to;
  options.control = args.control;
  if (!args.control_token_file.empty()) options.control_token = read_control_token(args.control_token_file);
  options.open_control = args.open_control;
  options.speed = parsed_or_input_error("", [&] { return stream::parse_speed(args.speed); });
  options.stepped = args.stepped;
  const std::uint32_t available = source->available_messages();
  options.destination_messages =
      args.messages.empty() ? (available & (stream::kSimulatedBit | stream::kRecordedBit))
                            : parsed_or_input_error("--messages", [&] { return stream::parse_message_mask(args.messages); });
  if ((options.destination_messages & ~available) != 0) {
    throw InputError(args.input, "--messages", "a scene has no recorded target lists (stream a recording directory for those)");
  }
  options.wait_clients = args.wait_clients;
  options.client_timeout_s = args.client_timeout_s;
  options.max_clients = args.max_clients;
  options.late_tolerance = std::chrono::nanoseconds(static_cast<std::int64_t>(args.late_ms * 1e6));
  options.multicast_ttl = args.ttl;
  if (!args.multicast_interface.empty()) {
    boost::system::error_code error;
    boost::asio::ip::make_address_v4(args.multicast_interface, error);
    if (error) throw InputError("rcsim stream", "--multicast-interface", "'" + args.multicast_interface + "' is not an IPv4 address");
  }
  options.multicast_interface = args.multicast_interface;
  if (args.from_cycle >= source->cycle_count()) {
    throw InputError(args.input, "--from-cycle", fmt::format("cycle {} is not in 0..{}", args.from_cycle, source->cycle_count() - 1));
  }
  options.first_cycle = args.from_cycle;
  options.hold_at_end = args.hold;
  options.handle_signals = true;
  options.queue_cycles = args.queue_cycles;
  options.realtime_priority = args.realtime;

  std::optional<stream::Streamer> streamer_holder;
  parsed_or_input_error("", [&] { return &streamer_holder.emplace(*source, options, std::cerr); });
  stream::Streamer& streamer = *streamer_holder;
  std::string sensors;
  for (const auto& id : source->sensor_ids()) sensors += (sensors.empty() ? "" : ", ") + id;
  std::cerr << fmt::format("rcsim stream: {}: {} cycles, sensors {}; speed {}{}", args.input, source->cycle_count(), sensors,
                           args.speed, args.stepped ? ", stepped" : "");
  for (const auto& to : args.to) std::cerr << "; to " << to;
  if (streamer.control_port() != 0) {
    std::cerr << "; control port " << streamer.control_port()
              << (args.open_control                      ? " (every client may steer)"
                  : !options.control_token.empty() ? " (clients with the control token steer, others watch)"
                                                   : " (clients watch; nobody steers without --control-token-file)");
  }
  std::cerr << std::endl;
  const stream::StreamSummary summary = streamer.run();
  std::cerr << summary.line() << std::endl;
}

}  // namespace

void add_stream_command(CLI::App& app) {
  auto args = std::make_shared<StreamArgs>();
  auto* cmd = app.add_subcommand("stream", "play a scene or a recording live over UDP, paced against a steady clock");
  cmd->add_option("input", args->input, "Scene file (rcsim-scene) or recording directory (rcsim-recording)")
      ->required()
      ->check(CLI::ExistingPath);
  cmd->add_option("--to", args->to, "Destination HOST:PORT, unicast or multicast (repeatable)");
  cmd->add_option("--control", args->control,
                  "Control port [HOST:]PORT where clients subscribe, pause, resume, step and seek (HOST defaults to 127.0.0.1)");
  cmd->add_option("--control-token-file", args->control_token_file,
                  "File whose first line is the control token: clients that present it may pause, resume, step and "
                  "seek; the others only watch")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--open-control", args->open_control,
                "Let every subscribed client steer playback, without a token (a machine whose users you trust)");
  cmd->add_option("--speed", args->speed, "1 real time, 10 ten times, max as fast as possible")->capture_default_str();
  cmd->add_flag("--stepped", args->stepped, "Start paused: a steering client's STEP lets cycles out (RESUME plays paced)");
  cmd->add_option("--messages", args->messages,
                  "What --to destinations get: simulated,recorded,truth (default: the target lists the input has)");
  cmd->add_option("--level", args->level, "tracks | detections")->check(CLI::IsMember({"tracks", "detections"}))->capture_default_str();
  add_seed_option(*cmd, args->seed, "Seed of every random draw");
  cmd->add_flag("--no-noise", args->no_noise, "Turn every random draw off");
  add_fidelity_option(*cmd, args->fidelity);
  cmd->add_option("--wait-clients", args->wait_clients, "Hold the first cycle until this many clients have subscribed")
      ->check(kNonNegative);
  cmd->add_option("--client-timeout-s", args->client_timeout_s, "Drop a client not heard from for this long")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--max-clients", args->max_clients, "Most clients subscribed at once")->capture_default_str();
  cmd->add_option("--late-ms", args->late_ms, "A cycle sent later than this after its deadline counts as late")
      ->check(kNonNegative)
      ->capture_default_str();
  cmd->add_option("--ttl", args->ttl, "Multicast hop limit")->check(CLI::Range(0, 255))->capture_default_str();
  cmd->add_option("--multicast-interface", args->multicast_interface, "IPv4 address of the interface multicast leaves from");
  cmd->add_option("--from-cycle", args->from_cycle, "First cycle to send (earlier ones are simulated, not sent)")
      ->check(kNonNegative);
  cmd->add_flag("--hold", args->hold, "After the last cycle keep the control port open (clients may seek back); stop with Ctrl-C");
  cmd->add_option("--queue-cycles", args->queue_cycles, "How many cycles the simulation may run ahead of the schedule")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}))
      ->capture_default_str();
  cmd->add_option("--realtime", args->realtime,
                  "Run the sending thread with SCHED_FIFO at this priority (1..99; needs CAP_SYS_NICE): steadier pacing on busy machines")
      ->check(CLI::Range(0, 99));
  cmd->callback([args] { run_stream(*args); });
}

}  // namespace rcsim::cli
