// fluidbed command line: run, check, report. Maps errors to the exit codes of shared/interface.md.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <iostream>
#include <memory>
#include <string>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <sys/wait.h>
#include <unistd.h>

#include "core/error.hpp"
#include "config/case_check.hpp"
#include "config/case_loader.hpp"
#include "parallel/launcher.hpp"
#include "parallel/mpi_comm.hpp"
#include "run/ensemble.hpp"
#include "run/runner.hpp"

#ifndef FLUIDBED_POST_DIR
#define FLUIDBED_POST_DIR "post"
#endif

namespace {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

int report(const std::vector<std::string>& dirs, const std::vector<std::string>& labels, const std::string& out,
           bool animate) {
  const char* env = std::getenv("FLUIDBED_POST_DIR");
  const std::filesystem::path post = env ? env : FLUIDBED_POST_DIR;
  const std::filesystem::path script = post / "report.py";
  if (!std::filesystem::exists(script)) {
    throw fluidbed::Error(fluidbed::ErrorKind::BadInput,
                          fmt::format("{} not found (set FLUIDBED_POST_DIR to the post/ folder)", script.string()));
  }
  for (const auto& d : dirs) {
    if (!std::filesystem::is_directory(d)) {
      throw fluidbed::Error(fluidbed::ErrorKind::BadInput, fmt::format("{}: not a run output folder", d));
    }
  }
  if (!labels.empty() && labels.size() != dirs.size()) {
    throw fluidbed::Error(fluidbed::ErrorKind::BadInput,
                          fmt::format("{} --label for {} run folders: give one per folder, in their order",
                                      labels.size(), dirs.size()));
  }
  std::string cmd = "/usr/bin/python3 " + shell_quote(script.string());
  for (const auto& d : dirs) cmd += " " + shell_quote(d);
  for (const auto& l : labels) cmd += " --label " + shell_quote(l);
  cmd += " --out " + shell_quote(out);
  if (animate) cmd += " --animate";
  const int rc = std::system(cmd.c_str());
  if (rc != -1 && WIFEXITED(rc) && WEXITSTATUS(rc) == 2) return 2;  // the script named the bad input
  if (rc != 0) {
    std::cerr << "fluidbed report: the report script failed\n";
    return 3;
  }
  return 0;
}

// Tasks other than this program that stay runnable: the fewest of five looks at /proc/loadavg's "running" count
// (less this process) over 20 ms, so that a program starting beside this one (the shell, a pipe's reader) does not
// count while a busy one (a build, another simulation) does; -1 when it cannot be read.
int other_runnable_tasks() {
  int fewest = -1;
  for (int look = 0; look < 5; ++look) {
    if (look > 0) usleep(5000);
    std::ifstream in("/proc/loadavg");
    double l1 = 0.0, l5 = 0.0, l15 = 0.0;
    std::string counts;
    if (!(in >> l1 >> l5 >> l15 >> counts)) return -1;
    const auto slash = counts.find('/');
    if (slash == std::string::npos) return -1;
    const int others = std::max(0, std::atoi(counts.substr(0, slash).c_str()) - 1);
    fewest = fewest < 0 ? others : std::min(fewest, others);
  }
  return fewest;
}

}  // namespace

int main(int argc, char** argv) {
  // How an OpenMP thread waits for the next parallel region (docs/performance.md, "Waiting threads"). A thread
  // that spins a while hands work over in microseconds instead of a sleep and wake-up each time: on the idle
  // 2-core machine the paper's DEM case ran 1.45 times and its TFM case 1.2 times faster at 2 threads. A spinning
  // thread that shares its core with another busy program takes that program's time and waits for its own partner
  // in turn: with one other busy task the DEM case ran 2.7-3.7 times slower. So threads spin (up to
  // GOMP_SPINCOUNT = 100000 polls, then sleep) only when no other task is runnable as the program starts, else
  // they sleep at once (passive). libgomp reads both when it loads, so set them and restart the program once,
  // unless the user chose either; the run's log says which was taken.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr) {
    const int others = other_runnable_tasks();
    const bool spin = others == 0;
    setenv("OMP_WAIT_POLICY", "passive", 1);
    setenv("GOMP_SPINCOUNT", spin ? "100000" : "0", 1);
    setenv("FLUIDBED_WAIT_NOTE",
           spin ? "threads spin up to 100000 polls before they sleep (no other task was runnable at the start)"
                : fmt::format("threads sleep when idle ({} other task{} runnable at the start)",
                              others < 0 ? std::string("?") : std::to_string(others), others == 1 ? " was" : "s were")
                      .c_str(),
           1);
    execv("/proc/self/exe", argv);  // returns only on failure: then go on with the default policy
  }
#ifdef __GLIBC__
  // Each time step allocates and frees the same temporaries (sparse matrices, fields). By default glibc serves
  // blocks over 128 KiB with mmap and trims the heap top, so every step page-faults them in again: 16% of the
  // CPU time of the paper's TFM case went to page faults. Keep freed memory in the process for reuse instead.
  mallopt(M_MMAP_THRESHOLD, 4 << 20);  // particle arrays of large beds (8 MB per million) still use mmap
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
  CLI::App app{"fluidbed: gas-fluidized beds by CFD-DEM and the two-fluid model"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "fluidbed 0.1.0");

  std::string case_file;
  std::vector<std::string> sets;
  fluidbed::RunOptions ro;
  double end_time = -1.0, max_wall = -1.0;
  auto* run = app.add_subcommand("run", "run a case");
  run->add_option("case", case_file, "case file (TOML)")->required();
  run->add_option("--out", ro.out_dir, "output folder (default out/<case name>)");
  run->add_option("--end-time", end_time, "simulated end time, s (overrides case.end_time)")->check(CLI::PositiveNumber);
  run->add_option("--threads", ro.threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 1024));
  run->add_option("--set", sets, "override a case key: SECTION.KEY=VALUE (repeatable)");
  run->add_option("--restart", ro.restart,
                  "continue from this HDF5 checkpoint, or 'latest': the valid one of the output folder with the "
                  "latest simulated time");
  run->add_flag("--overwrite", ro.overwrite, "a new run may replace the results already in the output folder");
  run->add_option("--allow-changed", ro.allow_changed,
                  "with --restart: accept this case key (or section) differing from the checkpoint's (repeatable)");
  run->add_option("--max-wall-time", max_wall, "stop with a checkpoint after this wall time, s")->check(CLI::PositiveNumber);
  run->add_flag("--quiet", ro.quiet, "no progress or log on the terminal (log.txt is still written)");

  std::string check_file;
  std::vector<std::string> check_sets;
  auto* check = app.add_subcommand("check", "validate a case and print its derived quantities");
  check->add_option("case", check_file, "case file (TOML)")->required();
  check->add_option("--set", check_sets, "override a case key: SECTION.KEY=VALUE (repeatable)");

  fluidbed::EnsembleOptions eo;
  double ens_end = -1.0;
  auto* ens = app.add_subcommand("ensemble", "run N packings of a case (case.seed, seed+1, ...) in parallel");
  ens->add_option("case", eo.case_file, "case file (TOML)")->required();
  ens->add_option("-n", eo.members, "number of members (default 8)")->check(CLI::Range(1, 10000));
  ens->add_option("--jobs", eo.jobs, "members running at once (default 2)")->check(CLI::Range(1, 1024));
  ens->add_option("--threads", eo.threads, "OpenMP threads per member (default 1)")->check(CLI::Range(1, 1024));
  ens->add_option("--out", eo.out_dir, "ensemble folder (default out/<case name>-ensemble)");
  ens->add_option("--end-time", ens_end, "simulated end time, s")->check(CLI::PositiveNumber);
  ens->add_option("--set", eo.sets, "override a case key for every member (repeatable)");
  ens->add_flag("--overwrite", eo.overwrite, "members may replace earlier results in their folders");
  ens->add_flag("--quiet", eo.quiet, "no progress on the terminal");

  auto* keys = app.add_subcommand("keys", "print every case key (type, unit, default, range) as Markdown");

  std::vector<std::string> report_dirs;
  std::string report_out = "report";
  auto* rep = app.add_subcommand("report", "figures and summary.md from one or more run folders");
  rep->add_option("dirs", report_dirs, "run output folders")->required();
  rep->add_option("--out", report_out, "report folder (default ./report)");
  std::vector<std::string> report_labels;
  rep->add_option("--label", report_labels,
                  "label of a run in legends and tables, once per folder in their order (default: the folder name)")
      ->allow_extra_args(false);  // one value per --label, so the folders may follow it
  bool report_animate = false;
  rep->add_flag("--animate", report_animate, "also write an animated GIF of voidage and particles per run");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }

  // Started by mpirun or srun on several processes: `run` splits the case over them (docs/parallel.md); an ensemble
  // already runs its members as processes of its own, so it is refused (once, by the first process).
  const fluidbed::LaunchedAs launch = fluidbed::launched_as();
  if (*ens && launch.size > 1) {
    if (launch.rank == 0) {
      std::cerr << fmt::format("fluidbed: started as {} processes by an MPI launcher (mpirun, srun): an ensemble runs "
                               "its members as processes of its own (--jobs); start it without the launcher, or run "
                               "each member with mpirun\n", launch.size);
    }
    return 2;
  }
  // The ranks of a run: MPI is started only when a launcher started several processes (one process is the serial
  // run of every earlier version).
  std::unique_ptr<fluidbed::Comm> mpi;
#ifdef FLUIDBED_HAVE_MPI
  if (*run && launch.size > 1) mpi = std::make_unique<fluidbed::MpiComm>();
#endif
  if (*run && launch.size > 1 && !mpi) {
    if (launch.rank == 0) std::cerr << "fluidbed: started on several processes, but built without MPI (libopenmpi-dev)\n";
    return 2;
  }
  const bool speaks = !mpi || mpi->rank() == 0;
  // A failure on several ranks: said once, by rank 0, when every rank met it (a verdict the ranks reached
  // together); a failure of one rank alone, which the others are waiting on in a collective, is said by that rank,
  // which then ends them all with its exit code.
  auto fail = [&](int code, const std::string& message) {
    if (mpi && !mpi->all_arrive_within(fluidbed::failure_verdict_seconds())) {
      std::cerr << fmt::format("fluidbed: rank {}: {}\n", mpi->rank(), message);
      std::cerr.flush();
      mpi->abort(code);
    }
    if (speaks) std::cerr << "fluidbed: " << message << "\n";
    return code;
  };

  try {
    if (*run) {
      ro.sets = sets;  // as given, for the command that continues an interrupted run
      if (end_time > 0) {
        ro.end_time = end_time;
        sets.push_back(fmt::format("case.end_time={}", end_time));
      }
      if (max_wall > 0) ro.max_wall_time = max_wall;
      const fluidbed::LoadedCase lc = fluidbed::load_case(case_file, sets);
      ro.comm = mpi.get();
      return fluidbed::run_case(lc, ro);
    }
    if (*check) {
      const fluidbed::LoadedCase lc = fluidbed::load_case(check_file, check_sets);
      fmt::print("{}: OK\n{}", check_file, fluidbed::describe_case(lc.config));
      return 0;
    }
    if (*rep) return report(report_dirs, report_labels, report_out, report_animate);
    if (*ens) {
      if (ens_end > 0) eo.end_time = ens_end;
      return fluidbed::run_ensemble(eo);
    }
    if (*keys) {
      fmt::print("{}", fluidbed::case_keys_markdown());
      return 0;
    }
  } catch (const fluidbed::Error& e) {
    return fail(e.exit_code(), e.what());
  } catch (const std::exception& e) {
    return fail(3, std::string("internal error: ") + e.what());
  }
  return 0;
}
