#pragma once
// A real one-node Slurm cluster for the campaign tests, started and stopped by the test itself:
// munged, slurmctld and slurmd from Debian's munge and slurm-wlm packages, in the foreground, as
// root, on loopback and free ports, with their key, sockets, state and logs under the test's
// scratch directory. Why each setting: docs/slurm-testing.md.
//
//   std::string why_not;
//   auto cluster = SlurmCluster::start(dir_, &why_not);
//   if (!cluster) GTEST_SKIP() << why_not;
//   const std::string job = cluster->sbatch("--array=0-3 --output=" + out + " " + script);
//   const auto states = cluster->wait(job, std::chrono::seconds(60));  // task id -> "COMPLETED"
//
// Keep the cluster a local of the test body (or reset it in TearDown before the scratch
// directory is removed): its destructor stops the daemons by pid and, when the test failed,
// prints the end of their logs.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <netinet/in.h>
#include <optional>
#include <random>
#include <sched.h>
#include <sstream>
#include <stdexcept>
#include <string>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <utility>
#include <vector>

#include "app/cli/run_rcsim.hpp"

extern char** environ;

namespace rcsim::testing {

namespace slurm_detail {

inline std::string shell_quote(const std::string& s) {
  std::string quoted = "'";
  for (const char c : s) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

inline std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// The command's stdout and stderr (except what the command redirects itself), and its exit code.
inline CommandResult shell(const std::string& command) {
  CommandResult result{0, {}};
  FILE* pipe = popen(("{ " + command + "\n} 2>&1").c_str(), "r");
  if (pipe == nullptr) return {127, "popen failed"};
  std::array<char, 4096> buffer{};
  while (const std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  return result;
}

// The named program in PATH or in the sbin directories (not in a non-root PATH), or empty.
inline std::filesystem::path find_program(const std::string& name) {
  std::string dirs = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  dirs += ":/usr/sbin:/sbin:/usr/bin";
  std::istringstream in(dirs);
  for (std::string dir; std::getline(in, dir, ':');) {
    if (dir.empty()) continue;
    const auto candidate = std::filesystem::path(dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

// A TCP port that was free on 127.0.0.1 a moment ago: the kernel's choice for port 0. `held`
// stays bound until the caller closes it, so that a second call gives a different port.
inline int free_port(int* held) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error("SlurmCluster: socket() failed");
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;
  socklen_t length = sizeof(address);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    ::close(fd);
    throw std::runtime_error("SlurmCluster: cannot bind a port on 127.0.0.1");
  }
  *held = fd;
  return ntohs(address.sin_port);
}

inline std::string tail(const std::filesystem::path& file, std::size_t lines) {
  std::ifstream in(file);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += all[i] + "\n";
  return out;
}

// The value of KEY= in one `scontrol -o show job` record, or empty.
inline std::string field(const std::string& record, const std::string& key) {
  const std::string padded = " " + record;
  const std::size_t at = padded.find(" " + key + "=");
  if (at == std::string::npos) return {};
  const std::size_t begin = at + key.size() + 2;
  return padded.substr(begin, padded.find(' ', begin) - begin);
}

}  // namespace slurm_detail

class SlurmCluster {
 public:
  static constexpr const char* node_name = "rcsim0";
  static constexpr const char* partition = "debug";

  // The cluster up with its node idle; nullopt and the reason when this machine cannot run one
  // (not root, packages missing): the test should then GTEST_SKIP. Throws, with the end of the
  // daemons' logs, when the cluster was expected to start and did not.
  static std::optional<SlurmCluster> start(const std::filesystem::path& scratch, std::string* why_not) {
    if (::geteuid() != 0) {
      *why_not = "a test Slurm cluster needs root (slurmd runs jobs as SlurmdUser=root)";
      return std::nullopt;
    }
    Programs programs;
    std::string missing;
    for (const auto& [name, path] : {std::pair{"munged", &programs.munged}, std::pair{"slurmctld", &programs.slurmctld},
                               std::pair{"slurmd", &programs.slurmd}}) {
      *path = slurm_detail::find_program(name);
      if (path->empty()) missing += std::string(" ") + name;
    }
    for (const char* name : {"sbatch", "squeue", "sinfo", "scontrol", "scancel"}) {
      const auto path = slurm_detail::find_program(name);
      if (path.empty()) missing += std::string(" ") + name;
      programs.clients = path.parent_path();
    }
    if (!missing.empty()) {
      *why_not = "Slurm or munge not installed (missing" + missing + "); scripts/setup.sh installs slurm-wlm and munge";
      return std::nullopt;
    }
    // Unix sockets (munged's, and slurmstepd's SPOOL/NODE_JOB.STEP) hold at most 107 bytes.
    const auto root = std::filesystem::absolute(scratch) / "slurm";
    if (root.string().size() + 40 > 107) {
      throw std::runtime_error("SlurmCluster: scratch path too long for Unix sockets: " + root.string());
    }
    std::string failures;
    for (int attempt = 1; attempt <= 3; ++attempt) {
      SlurmCluster cluster(std::make_unique<State>());
      std::string failure;
      if (cluster.state_->start(root, programs, &failure)) return cluster;
      failures += "attempt " + std::to_string(attempt) + ": " + failure + "\n";
      // Another process can take a free port before the daemon binds it: try again on new ports.
      if (failure.find("Address already in use") == std::string::npos) break;
    }
    throw std::runtime_error("SlurmCluster did not start:\n" + failures);
  }

  const std::filesystem::path& conf() const { return state_->conf; }
  // "SLURM_CONF=/…/slurm.conf": what client commands (sbatch, squeue, scontrol, scancel, sinfo
  // and `rcsim campaign submit`) need in their environment to reach this cluster.
  std::string env() const { return "SLURM_CONF=" + state_->conf.string(); }
  int cpus() const { return state_->cpus; }
  // munged, slurmctld, slurmd.
  std::vector<pid_t> daemon_pids() const { return {state_->munged, state_->slurmctld, state_->slurmd}; }

  // COMMAND through the shell, in the scratch directory (so that jobs without --output or
  // --chdir write there), with env() and without the caller's own SLURM_*/SBATCH_* variables.
  // The output holds stdout and stderr, unless COMMAND redirects stderr itself (`2>/dev/null`).
  CommandResult run(const std::string& command) const { return slurm_detail::shell(state_->client_prefix() + command); }

  // `sbatch --parsable ARGS`: the job id. Throws with sbatch's message when it refuses.
  std::string sbatch(const std::string& args) const {
    const auto result = run("sbatch --parsable " + args);
    const std::string id = slurm_detail::trim(result.output.substr(0, result.output.find(';')));
    if (result.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
      throw std::runtime_error("sbatch " + args + " failed: " + result.output);
    }
    return id;
  }

  // `scancel JOB` (JOB, or JOB_TASK for one array task).
  void cancel(const std::string& job) const {
    const auto result = run("scancel " + job);
    if (result.exit_code != 0) throw std::runtime_error("scancel " + job + " failed: " + result.output);
  }

  // Waits until nothing of JOB is pending or running; returns each task's final state
  // (COMPLETED, FAILED, CANCELLED, TIMEOUT, ...) by array task id (-1 for a job without an
  // array). Slurm keeps finished jobs for MinJobAge (300 s) to answer this. Throws on timeout.
  std::map<int, std::string> wait(const std::string& job, std::chrono::seconds timeout) const {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      const auto queued = run("squeue -h -o %i -j " + job);
      if (queued.exit_code == 0 && slurm_detail::trim(queued.output).empty()) break;
      if (queued.output.find("Invalid job id") != std::string::npos) break;
      if (std::chrono::steady_clock::now() > deadline) {
        throw std::runtime_error("job " + job + " still queued after " + std::to_string(timeout.count()) +
                                 " s:\n" + run("squeue -j " + job).output + log_tails(20));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    std::map<int, std::string> states;
    std::istringstream records(run("scontrol -o show job " + job).output);
    for (std::string record; std::getline(records, record);) {
      const std::string state = slurm_detail::field(record, "JobState");
      if (state.empty()) continue;
      const std::string task = slurm_detail::field(record, "ArrayTaskId");
      const bool single = !task.empty() && task.find_first_not_of("0123456789") == std::string::npos;
      states[single ? std::stoi(task) : -1] = state;
    }
    return states;
  }

  // The last LINES lines of each daemon's log.
  std::string log_tails(std::size_t lines) const { return state_->log_tails(lines); }

 private:
  struct Programs {
    std::filesystem::path munged, slurmctld, slurmd;
    std::filesystem::path clients;  // the directory of sbatch, squeue, ...
  };

  // Everything the daemons need, held behind a pointer so that the cluster moves (into the
  // optional) without stopping anything; its destructor stops the daemons.
  struct State {
    std::filesystem::path root, conf, munge_socket;
    std::string path;  // PATH for client commands: the clients' directory first
    std::filesystem::path munged_log, slurmctld_log, slurmd_log;
    pid_t munged = -1, slurmctld = -1, slurmd = -1;
    int cpus = 1;
    long memory_mb = 100;

    State() = default;
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    ~State() { stop(); }

    std::string client_prefix() const {
      std::string prefix = "cd " + slurm_detail::shell_quote(root.parent_path().string()) + " || exit 1; ";
      for (char** e = environ; *e != nullptr; ++e) {
        const std::string entry(*e);
        const std::string name = entry.substr(0, entry.find('='));
        if (name.rfind("SLURM_", 0) == 0 || name.rfind("SBATCH_", 0) == 0 || name.rfind("SQUEUE_", 0) == 0) {
          prefix += "unset " + name + "; ";
        }
      }
      return prefix + "export PATH=" + slurm_detail::shell_quote(path) +
             " SLURM_CONF=" + slurm_detail::shell_quote(conf.string()) + "; ";
    }

    std::string log_tails(std::size_t lines) const {
      std::string out;
      for (const auto& log : {munged_log, slurmctld_log, slurmd_log}) {
        out += "--- " + log.string() + " (last " + std::to_string(lines) + " lines)\n" + slurm_detail::tail(log, lines);
      }
      return out;
    }

    // Forks and executes ARGV with stdout and stderr appended to LOG. The daemon gets SIGTERM
    // when the test process dies (a crash, a CTest timeout), so none outlives its test.
    static pid_t spawn(const std::vector<std::string>& argv, const std::filesystem::path& log) {
      std::vector<char*> args;
      for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
      args.push_back(nullptr);
      const std::string log_path = log.string();
      const pid_t parent = ::getpid();
      const pid_t pid = ::fork();
      if (pid < 0) throw std::runtime_error("SlurmCluster: fork failed");
      if (pid > 0) return pid;
      // Child: only async-signal-safe calls until exec.
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (::getppid() != parent) ::_exit(127);
      const int null_fd = ::open("/dev/null", O_RDONLY);
      const int log_fd = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (null_fd < 0 || log_fd < 0) ::_exit(127);
      ::dup2(null_fd, 0);
      ::dup2(log_fd, 1);
      ::dup2(log_fd, 2);
      for (int fd = 3; fd < 1024; ++fd) ::close(fd);
      ::execv(args[0], args.data());
      ::_exit(127);
    }

    // Whether PID (our child) is still running; reaps it if not.
    static bool running(pid_t& pid) {
      if (pid <= 0) return false;
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == 0) return true;
      pid = -1;
      return false;
    }

    void write_files(const std::filesystem::path& at, int slurmctld_port, int slurmd_port) {
      namespace fs = std::filesystem;
      root = at;
      fs::remove_all(root);  // a previous attempt's files (only ever inside the scratch directory)
      for (const char* sub : {"munge", "state", "spool", "log"}) fs::create_directories(root / sub);
      // munged refuses a socket whose directories are not searchable by everyone.
      const auto searchable = fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec;
      fs::permissions(root.parent_path(), fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
      for (const auto& dir : {root, root / "munge"}) fs::permissions(dir, searchable);
      // munged refuses a key readable by anyone but its owner.
      const auto key = root / "munge" / "munge.key";
      {
        std::random_device random;
        std::ofstream out(key, std::ios::binary);
        for (int i = 0; i < 256; ++i) {
          const auto word = random();
          out.write(reinterpret_cast<const char*>(&word), sizeof(word));
        }
      }
      fs::permissions(key, fs::perms::owner_read | fs::perms::owner_write);
      munge_socket = root / "munge" / "munge.socket";
      munged_log = root / "log" / "munged.log";
      slurmctld_log = root / "log" / "slurmctld.log";
      slurmd_log = root / "log" / "slurmd.log";
      cpus = std::max(1, static_cast<int>(::sysconf(_SC_NPROCESSORS_ONLN)));
      cpu_set_t affinity;
      if (::sched_getaffinity(0, sizeof(affinity), &affinity) == 0) cpus = std::max(1, CPU_COUNT(&affinity));
      // The machine's memory, so that a script asking for --mem=… fits (CR_CPU does not track it).
      const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGE_SIZE);
      memory_mb = pages > 0 && page_size > 0 ? std::max(100L, pages / (1024L * 1024L / page_size)) : 1024L;
      conf = root / "slurm.conf";
      const auto r = root.string();
      std::ofstream out(conf);
      out << "# A one-node test cluster on loopback, written by tests/end_to_end/slurm_cluster.hpp;\n"
          << "# docs/slurm-testing.md says why each line.\n"
          << "ClusterName=rcsimtest\n"
          << "SlurmctldHost=localhost(127.0.0.1)\n"
          << "SlurmctldPort=" << slurmctld_port << "\n"
          << "SlurmdPort=" << slurmd_port << "\n"
          << "SlurmUser=root\n"
          << "SlurmdUser=root\n"
          << "AuthType=auth/munge\n"
          << "AuthInfo=socket=" << munge_socket.string() << "\n"
          << "CredType=cred/munge\n"
          << "StateSaveLocation=" << r << "/state\n"
          << "SlurmdSpoolDir=" << r << "/spool\n"
          << "SlurmctldPidFile=" << r << "/slurmctld.pid\n"
          << "SlurmdPidFile=" << r << "/slurmd.pid\n"
          << "SlurmctldLogFile=" << slurmctld_log.string() << "\n"
          << "SlurmdLogFile=" << slurmd_log.string() << "\n"
          << "ProctrackType=proctrack/linuxproc\n"
          << "TaskPlugin=task/none\n"
          << "MpiDefault=none\n"
          << "JobAcctGatherType=jobacct_gather/none\n"
          << "AccountingStorageType=accounting_storage/none\n"
          << "JobCompType=jobcomp/none\n"
          << "MailProg=/bin/true\n"
          << "SchedulerType=sched/backfill\n"
          << "SchedulerParameters=sched_interval=1,bf_interval=1,batch_sched_delay=0,sched_min_interval=0\n"
          << "SelectType=select/cons_tres\n"
          << "SelectTypeParameters=CR_CPU\n"
          << "SlurmdParameters=config_overrides\n"
          << "ReturnToService=2\n"
          << "KillWait=2\n"
          << "MinJobAge=300\n"
          << "NodeName=" << node_name << " NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=" << cpus
          << " RealMemory=" << memory_mb << " State=UNKNOWN\n"
          << "PartitionName=" << partition << " Nodes=" << node_name << " Default=YES MaxTime=INFINITE State=UP\n";
    }

    bool start(const std::filesystem::path& at, const Programs& programs, std::string* failure) {
      int held_a = -1, held_b = -1;
      const int slurmctld_port = slurm_detail::free_port(&held_a);
      const int slurmd_port = slurm_detail::free_port(&held_b);
      ::close(held_a);
      ::close(held_b);
      write_files(at, slurmctld_port, slurmd_port);
      path = programs.clients.string() + (std::getenv("PATH") != nullptr ? std::string(":") + std::getenv("PATH") : "");
      const auto dir = (root / "munge").string();
      munged = spawn({programs.munged.string(), "--foreground", "--force", "--socket=" + munge_socket.string(),
                      "--key-file=" + dir + "/munge.key", "--pid-file=" + dir + "/munged.pid",
                      "--seed-file=" + dir + "/munged.seed", "--log-file=" + munged_log.string()},
                     munged_log);
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
      while (!std::filesystem::exists(munge_socket)) {
        if (!running(munged) || std::chrono::steady_clock::now() > deadline) {
          *failure = "munged did not create its socket\n" + log_tails(20);
          return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      slurmctld = spawn({programs.slurmctld.string(), "-D", "-f", conf.string()}, root / "log" / "slurmctld.stderr");
      slurmd = spawn({programs.slurmd.string(), "-D", "-f", conf.string(), "-N", node_name},
                     root / "log" / "slurmd.stderr");
      // Idle: registered with slurmctld and ready for jobs (not idle*, drain or down).
      for (;;) {
        if (!running(slurmctld) || !running(slurmd)) {
          *failure = std::string(slurmctld < 0 ? "slurmctld" : "slurmd") + " exited during start-up\n" +
                     slurm_detail::tail(root / "log" / "slurmctld.stderr", 10) +
                     slurm_detail::tail(root / "log" / "slurmd.stderr", 10) + log_tails(20);
          return false;
        }
        if (slurm_detail::trim(slurm_detail::shell(client_prefix() + "sinfo -h -o %T").output) == "idle") return true;
        if (std::chrono::steady_clock::now() > deadline) {
          *failure = "the node was not idle within 30 s: " + slurm_detail::shell(client_prefix() + "sinfo").output +
                     log_tails(20);
          return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }

    // Cancels what still runs (killing the jobs' processes through slurmd, which a signal to
    // the daemons would not), then SIGTERM to each daemon, SIGKILL to any still there after 10 s.
    void stop() {
      if (::testing::Test::HasFailure() && !root.empty()) std::cerr << log_tails(30);
      if (running(slurmctld) && running(slurmd)) {
        const auto queued = slurm_detail::shell(client_prefix() + "squeue -h -o %i");
        if (queued.exit_code == 0 && !slurm_detail::trim(queued.output).empty()) {
          slurm_detail::shell(client_prefix() + "scancel --partition=" + partition);
          const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
          while (std::chrono::steady_clock::now() < deadline &&
                 !slurm_detail::trim(slurm_detail::shell(client_prefix() + "squeue -h -o %i").output).empty()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
          }
        }
      }
      for (const pid_t pid : {slurmd, slurmctld, munged}) {
        if (pid > 0) ::kill(pid, SIGTERM);
      }
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      for (pid_t* pid : {&slurmd, &slurmctld, &munged}) {
        while (running(*pid) && std::chrono::steady_clock::now() < deadline) {
          std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (*pid > 0) {
          ::kill(*pid, SIGKILL);
          ::waitpid(*pid, nullptr, 0);
          *pid = -1;
        }
      }
    }
  };

  explicit SlurmCluster(std::unique_ptr<State> state) : state_(std::move(state)) {}

  std::unique_ptr<State> state_;
};

}  // namespace rcsim::testing
