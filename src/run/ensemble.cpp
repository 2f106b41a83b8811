#include "run/ensemble.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "config/case_loader.hpp"

namespace fluidbed {

namespace fs = std::filesystem;

std::vector<std::uint64_t> ensemble_seeds(std::uint64_t first, int members) {
  std::vector<std::uint64_t> s;
  for (int k = 0; k < members; ++k) s.push_back(first + static_cast<std::uint64_t>(k));
  return s;
}

namespace {

std::string json_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

/// The arguments of one member's `fluidbed run`.
std::vector<std::string> member_args(const EnsembleOptions& o, const LoadedCase& lc, std::uint64_t seed,
                                     const fs::path& dir) {
  std::vector<std::string> a{"fluidbed", "run", o.case_file, "--out", dir.string(), "--threads",
                             std::to_string(o.threads), "--quiet"};
  for (const std::string& s : o.sets) a.insert(a.end(), {"--set", s});
  a.insert(a.end(), {"--set", fmt::format("case.seed={}", seed)});
  // Each packing settles on its own: a shared settle.cache would give every member the first member's bed.
  if (!lc.config.settle.cache.empty())
    a.insert(a.end(), {"--set", fmt::format("settle.cache=\"{}\"", (fs::absolute(dir) / "settled-bed.csv").string())});
  if (o.end_time) a.insert(a.end(), {"--end-time", fmt::format("{}", *o.end_time)});
  if (o.overwrite) a.push_back("--overwrite");
  return a;
}

pid_t spawn(const std::vector<std::string>& args, bool share_cores) {
  const pid_t pid = ::fork();
  if (pid < 0) throw_simulation_error(fmt::format("ensemble: cannot start a member: {}", std::strerror(errno)));
  if (pid == 0) {
    // Members running side by side share the cores: their threads sleep when idle, unless the user chose how
    // they wait (apps/fluidbed/main.cpp: a spinning thread on a shared core slows both programs).
    if (share_cores && std::getenv("FLUIDBED_WAIT_NOTE") != nullptr) {
      setenv("GOMP_SPINCOUNT", "0", 1);
      setenv("FLUIDBED_WAIT_NOTE", "threads sleep when idle (an ensemble member among others running at once)", 1);
    }
    std::vector<char*> argv;
    for (const std::string& s : args) argv.push_back(const_cast<char*>(s.c_str()));
    argv.push_back(nullptr);
    ::execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  return pid;
}

}  // namespace

int run_ensemble(const EnsembleOptions& o) {
  if (o.members < 1) throw_input_error("ensemble: -n must be at least 1");
  if (o.jobs < 1) throw_input_error("ensemble: --jobs must be at least 1");
  std::vector<std::string> sets = o.sets;
  if (o.end_time) sets.push_back(fmt::format("case.end_time={}", *o.end_time));
  const LoadedCase lc = load_case(o.case_file, sets);  // a bad case fails here, before any member starts
  const fs::path out = o.out_dir.empty() ? fs::path("out") / (lc.config.name + "-ensemble") : fs::path(o.out_dir);
  ensure_directory(out);
  const std::vector<std::uint64_t> seeds = ensemble_seeds(lc.config.seed, o.members);
  std::vector<std::string> names;
  for (std::uint64_t s : seeds) names.push_back(fmt::format("seed-{}", s));

  std::map<pid_t, std::size_t> running;
  std::vector<int> rc(seeds.size(), -1);
  std::size_t next = 0;
  const auto log = [&](const std::string& line) {
    if (!o.quiet) std::cerr << line << "\n";
  };
  log(fmt::format("ensemble of {} members of {} ({} at a time, {} thread{} each) in {}", seeds.size(), lc.config.name,
                  o.jobs, o.threads, o.threads == 1 ? "" : "s", out.string()));
  while (next < seeds.size() || !running.empty()) {
    while (next < seeds.size() && running.size() < static_cast<std::size_t>(o.jobs)) {
      const fs::path dir = out / names[next];
      running[spawn(member_args(o, lc, seeds[next], dir), o.jobs > 1)] = next;
      log(fmt::format("  {} started", names[next]));
      ++next;
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw_simulation_error(fmt::format("ensemble: waiting for the members: {}", std::strerror(errno)));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const std::size_t k = it->second;
    running.erase(it);
    rc[k] = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
    log(fmt::format("  {} ended, exit {}", names[k], rc[k]));
  }

  std::string json = fmt::format("{{\"case\": {}, \"case_file\": {}, \"members\": [", json_string(lc.config.name),
                                 json_string(fs::absolute(o.case_file).string()));
  for (std::size_t k = 0; k < seeds.size(); ++k) {
    json += fmt::format("{}{{\"folder\": {}, \"seed\": {}, \"exit\": {}}}", k ? ", " : "", json_string(names[k]),
                        seeds[k], rc[k]);
  }
  json += "]}\n";
  write_file_atomic(out / "ensemble.json", json);
  std::vector<std::string> failed;
  for (std::size_t k = 0; k < seeds.size(); ++k)
    if (rc[k] != 0) failed.push_back(fmt::format("{} (exit {}, see {})", names[k], rc[k], (out / names[k] / "log.txt").string()));
  if (!failed.empty()) {
    std::cerr << fmt::format("fluidbed ensemble: {} of {} members failed: {}\n", failed.size(), seeds.size(),
                             fmt::join(failed, "; "));
    return 3;
  }
  log(fmt::format("ensemble done: {} members in {}; report with: fluidbed report {}", seeds.size(), out.string(),
                  out.string()));
  return 0;
}

}  // namespace fluidbed
