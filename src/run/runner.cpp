#include "run/runner.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <csignal>
#include <filesystem>
#include <limits>
#include <span>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <sys/file.h>
#include <unistd.h>
#include <variant>

#include "analysis/bed_surface.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/layer_tracers.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "run/average_series.hpp"
#include "run/bubble_series.hpp"
#include "run/probe_series.hpp"
#include "run/checkpoint_set.hpp"
#include "io/csv.hpp"
#include "models/dem_model.hpp"
#include "models/tfm_model.hpp"
#include "io/hdf5_file.hpp"
#include "io/pvd.hpp"
#include "io/vtk_writer.hpp"
#include "run/analysis_csv.hpp"

namespace fluidbed {

namespace fs = std::filesystem;

namespace {

// The one process-wide value: a signal handler can reach nothing else.
std::atomic<int> pending_signal{0};
extern "C" void on_signal(int sig) { pending_signal.store(sig); }

class Progress {
 public:
  Progress(bool quiet, double t_start, double t_end)
      : quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0 && std::getenv("CI") == nullptr), t_start_(t_start),
        t_end_(t_end), next_percent_(0) {
    if (t_end_ > t_start_) next_percent_ = static_cast<int>(std::floor(100.0 * t_start_ / t_end_ / 5.0)) * 5 + 5;
  }

  void update(double t, std::uint64_t steps, double wall, spdlog::logger& log) {
    if (quiet_) return;
    const double frac = std::clamp((t - t_start_) / std::max(t_end_ - t_start_, 1e-300), 0.0, 1.0);
    const double eta = frac > 0.0 ? wall * (1.0 - frac) / frac : 0.0;
    const double percent = 100.0 * t / t_end_;
    if (tty_) {
      if (wall - last_draw_ < 0.2 && frac < 1.0) return;
      last_draw_ = wall;
      fmt::print(stderr, "\r  t = {:.4f} s  {:5.1f}%  {:8.0f} steps/s  wall {:7.1f} s  ETA {:7.1f} s ", t, percent,
                 steps / std::max(wall, 1e-9), wall, eta);
      std::fflush(stderr);
    } else if (percent + 1e-9 >= next_percent_) {
      log.info("t = {:.4f} s ({:.0f}%), {:.0f} steps/s, wall {:.1f} s, ETA {:.1f} s", t, percent,
               steps / std::max(wall, 1e-9), wall, eta);
      while (next_percent_ <= percent + 1e-9) next_percent_ += 5;
    }
  }
  void finish() {
    if (!quiet_ && tty_) fmt::print(stderr, "\n");
  }

 private:
  bool quiet_, tty_;
  double t_start_, t_end_;
  int next_percent_;
  double last_draw_ = -1.0;
};

/// The log of a rank other than 0: nothing (rank 0 writes the run's one log).
std::shared_ptr<spdlog::logger> make_silent_logger() {
  return std::make_shared<spdlog::logger>("fluidbed", std::make_shared<spdlog::sinks::null_sink_mt>());
}

std::shared_ptr<spdlog::logger> make_logger(const fs::path& out, bool quiet, bool append) {
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>((out / "log.txt").string(), !append);
  file->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
  std::vector<spdlog::sink_ptr> sinks{file};
  if (!quiet) {
    auto console = std::make_shared<spdlog::sinks::stderr_sink_mt>();
    console->set_pattern("%v");
    sinks.push_back(console);
  }
  auto log = std::make_shared<spdlog::logger>("fluidbed", sinks.begin(), sinks.end());
  log->flush_on(spdlog::level::info);
  return log;
}

// An output stamped k * interval stands for the model time t when they agree to this fraction of the interval:
// far below any time step, far above the rounding a sum of steps accumulates (1e-12 relative after 10^4 steps).
constexpr double kStampTolerance = 1e-6;

/// Scheduled output: the k-th event is due at k * interval.
struct Schedule {
  double interval = 0.0;
  std::int64_t next = 0;
  bool due(double t, double dt) const { return interval > 0.0 && t >= next * interval - slack(dt); }
  void advance(double t, double dt) {
    while (interval > 0.0 && t >= next * interval - slack(dt)) ++next;
  }
  double slack(double dt) const { return std::max(0.5 * dt, 1e-9 * interval); }
  /// The time written for the event due at model time t: exactly k * interval when t is that instant up to
  /// rounding (a sum of steps gives 0.19001999999995264 for 0.19), else t itself (a step that does not divide
  /// the interval).
  double stamp(double t) const {
    const double scheduled = static_cast<double>(next) * interval;
    return std::abs(t - scheduled) <= kStampTolerance * interval ? scheduled : t;
  }
};

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();

void save_bubble_state(Hdf5File& f, const BubbleTracker::State& s) {
  f.create_group("bubble");
  f.write("bubble/tracked", std::vector<std::int32_t>(s.tracked.begin(), s.tracked.end()));
  f.write("bubble/nose_t", s.nose_t);
  f.write("bubble/nose_h", s.nose_h);
  f.set_attribute("bubble", "tracking", static_cast<std::int64_t>(s.tracking));
  f.set_attribute("bubble", "was_attached", static_cast<std::int64_t>(s.was_attached));
  f.set_attribute("bubble", "bubble_count", static_cast<std::int64_t>(s.bubble_count));
  f.set_attribute("bubble", "detachment_time", s.detachment_time.value_or(kNone));
  f.set_attribute("bubble", "eruption_time", s.eruption_time.value_or(kNone));
  f.write("bubble/centroid_h", s.centroid_h);
}

BubbleTracker::State load_bubble_state(const Hdf5File& f) {
  BubbleTracker::State s;
  const auto tracked = f.read_int32("bubble/tracked");
  s.tracked.assign(tracked.begin(), tracked.end());
  s.nose_t = f.read_double("bubble/nose_t");
  s.nose_h = f.read_double("bubble/nose_h");
  s.tracking = f.attribute_int64("bubble", "tracking") != 0;
  s.was_attached = f.attribute_int64("bubble", "was_attached") != 0;
  s.bubble_count = static_cast<int>(f.attribute_int64("bubble", "bubble_count"));
  const double det = f.attribute_double("bubble", "detachment_time");
  const double eru = f.attribute_double("bubble", "eruption_time");
  if (!std::isnan(det)) s.detachment_time = det;
  if (!std::isnan(eru)) s.eruption_time = eru;
  // Older checkpoints lack it: the centroid velocity then starts again from the restart.
  if (f.has("bubble/centroid_h")) s.centroid_h = f.read_double("bubble/centroid_h");
  return s;
}

// The layer tracer balls (the paper's Fig. 4b/c) of a 2D or a 3D run.
using TracerBalls = std::variant<BallTracers<2>, BallTracers<3>>;

// Balls over the bed of the initial voidage, one per cell below its surface; none without a bed.
template <int Dim>
std::optional<TracerBalls> fresh_tracers(const FieldView& fv, int layers) {
  const CellGeometry<Dim> geo = fv.geometry<Dim>();
  const double h = fv.eps ? bed_surface_height<Dim>(CellView<Dim>{geo, fv.eps}).value_or(0.0) : 0.0;
  if (!(h > 0.0)) return std::nullopt;
  return TracerBalls(std::in_place_type<BallTracers<Dim>>, geo, h, layers);
}

void save_tracers(Hdf5File& f, const TracerBalls& balls) {
  std::visit([&](const auto& t) {
    f.create_group("tracers");
    f.write("tracers/id", t.id);
    f.write("tracers/x", t.x);
    f.write("tracers/y", t.y);
    if (!t.z.empty()) f.write("tracers/z", t.z);
    f.write("tracers/layer", t.layer);
  }, balls);
}

template <int Dim>
TracerBalls load_tracers(const Hdf5File& f, const FieldView& fv) {
  try {
    std::array<std::vector<double>, Dim> pos;
    pos[0] = f.read_double("tracers/x");
    pos[1] = f.read_double("tracers/y");
    if constexpr (Dim == 3) pos[2] = f.read_double("tracers/z");
    return TracerBalls(std::in_place_type<BallTracers<Dim>>, fv.geometry<Dim>(), f.read_int64("tracers/id"),
                       std::move(pos), f.read_int32("tracers/layer"));
  } catch (const Error& e) {
    throw_input_error(fmt::format("{}: {}", f.path().string(), e.what()));
  }
}

// One step of the balls with the model's solids velocity (cell centres, every component).
void advance_tracers(TracerBalls& balls, const FieldView& fv, double dt) {
  std::visit([&]<int Dim>(BallTracers<Dim>& t) {
    const CellGeometry<Dim> geo = fv.geometry<Dim>();
    std::array<CellView<Dim>, Dim> u;
    for (int a = 0; a < Dim; ++a) u[static_cast<std::size_t>(a)] = CellView<Dim>{geo, fv.us[static_cast<std::size_t>(a)]};
    t.advance(u, dt);
  }, balls);
}

const char* model_key(Model m) { return m == Model::Tfm ? "tfm" : "dem"; }
std::string model_words(const std::string& key) {
  return key == "tfm" ? "the two-fluid model (TFM)" : key == "dem" ? "the discrete-particle model (CFD-DEM)" : "model '" + key + "'";
}

// A word as the shell reads it: quoted only when it holds more than letters, digits and path punctuation.
std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                       "0123456789_-+=.,/:@%") == std::string::npos;
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// The results a run writes into its folder: the series files and the folders of frames and checkpoints.
constexpr std::array<const char*, 12> kResultFiles{"monitor.csv",       "fields.pvd",        "particles.pvd",
                                                   "bubble.csv",        "cost.json",         "bubbles.csv",
                                                   "bubble_events.csv", "bubble_frames.csv", "probes.csv",
                                                   "averages.vti",      "averages.csv",      "averages.json"};
constexpr std::array<const char*, 4> kResultFolders{"checkpoints", "fields", "particles", "tracers"};

/// What in `out` is the result of an earlier run, for the refusal to overwrite it.
std::vector<std::string> earlier_results(const fs::path& out) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const char* file : kResultFiles) {
    if (fs::exists(out / file, ec)) found.push_back(file);
  }
  for (const char* sub : kResultFolders) {
    if (fs::is_directory(out / sub, ec) && !fs::is_empty(out / sub, ec)) found.push_back(std::string(sub) + "/");
  }
  return found;
}

/// Temporaries NAME.tmp.<pid> of a process that no longer runs (a run killed while writing): never data.
int remove_stale_temporaries(const fs::path& out) {
  int removed = 0;
  std::error_code ec;
  std::vector<fs::path> dirs{out};
  for (const char* sub : kResultFolders) dirs.push_back(out / sub);
  for (const fs::path& dir : dirs) {
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      const std::size_t at = name.rfind(".tmp.");
      if (at == std::string::npos) continue;
      const long pid = std::strtol(name.c_str() + at + 5, nullptr, 10);
      const bool alive = pid != static_cast<long>(::getpid()) &&
                         (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
      if (pid <= 0 || alive) continue;
      if (fs::remove(e.path(), ec)) ++removed;
    }
  }
  return removed;
}

/// An output folder belongs to one run at a time: two runs writing the same series would interleave them. The
/// lock is flock() on <out>/.lock, which the kernel drops when the process ends (kill -9 included).
class FolderLock {
 public:
  explicit FolderLock(const fs::path& out) {
    ensure_directory(out);
    const fs::path file = out / ".lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw_input_error(fmt::format("cannot write {}: {}", file.string(), std::strerror(errno)));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      char pid[32] = {};
      const ssize_t n = ::pread(fd_, pid, sizeof pid - 1, 0);
      ::close(fd_);
      throw_input_error(fmt::format("{} is in use by another fluidbed run{}: wait for it to end, or stop it "
                                    "(touch {})", out.string(), n > 0 ? fmt::format(" (pid {})", pid) : "",
                                    (out / "STOP").string()));
    }
    const std::string me = std::to_string(static_cast<long long>(::getpid()));
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, me.data(), me.size(), 0) < 0) {
      // The pid is only for the message of a second run; the lock itself holds.
    }
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  ~FolderLock() { ::close(fd_); }

 private:
  int fd_ = -1;
};

/// The run: stages in the order they happen (execute()), the observers that write outputs, and the checkpoint.
class Run {
 public:
  Run(const LoadedCase& loaded, const RunOptions& options)
      : loaded_(loaded),
        options_(options),
        comm_(options.comm ? *options.comm : serial_comm()),
        root_(comm_.rank() == 0),
        cfg_(loaded.config),
        restart_(!options.restart.empty()) {
    if (options_.max_wall_time) cfg_.run.max_wall_time = *options_.max_wall_time;
    if (options_.end_time) cfg_.run.end_time = *options_.end_time;
    out_ = options_.out_dir.empty() ? fs::path("out") / cfg_.name : fs::path(options_.out_dir);
  }

  int execute() {
    std::optional<FolderLock> lock;
    on_root([&] { lock.emplace(out_); });
    if (restart_) choose_checkpoint();  // before anything in the folder changes: a refused restart leaves it as it was
    prepare_folder();
    try {
      // The resolved case (with command-line overrides) makes any run repeatable.
      on_root([&] { write_file_atomic(out_ / "case.toml", loaded_.resolved_toml); });
      build_model();
      restore_state();
      open_series();
      restart_file_.reset();
      step_until_end();
      return finish();
    } catch (const WriteError& e) {
      output_failed(e);
    }
  }

 private:
  // ---- stages ------------------------------------------------------------------------------------------------

  /// The checkpoint to continue from (`latest`: the newest valid one), verified and checked against the case by
  /// rank 0; every rank then reads it.
  void choose_checkpoint() {
    on_root([&] { choose_checkpoint_here(); });
    Bytes path;
    if (root_) {
      const std::string p = restart_path_.string();
      path.assign(reinterpret_cast<const std::byte*>(p.data()), reinterpret_cast<const std::byte*>(p.data()) + p.size());
    }
    comm_.broadcast(path, 0);
    if (!root_) {
      restart_path_ = std::string(reinterpret_cast<const char*>(path.data()), path.size());
      restart_file_.emplace(Hdf5File::open(restart_path_));
    }
  }

  void choose_checkpoint_here() {
    if (options_.restart == "latest") {
      const LatestCheckpoint latest = find_latest_checkpoint(out_ / "checkpoints");
      skipped_ = latest.skipped;
      if (latest.path.empty()) {
        std::string why = skipped_.empty() ? "there is none" : "none passes its check: " + skipped_.front();
        for (std::size_t k = 1; k < skipped_.size(); ++k) why += "; " + skipped_[k];
        throw_input_error(fmt::format("--restart latest: no checkpoint to continue from in {} ({})",
                                      (out_ / "checkpoints").string(), why));
      }
      restart_path_ = latest.path;
    } else {
      restart_path_ = options_.restart;
      if (!fs::exists(restart_path_)) throw_input_error(fmt::format("{}: restart file not found", options_.restart));
    }
    restart_file_.emplace(Hdf5File::open(restart_path_));
    restart_file_->verify();
    check_checkpoint_matches(*restart_file_);
  }

  void check_checkpoint_matches(const Hdf5File& f) const {
    const std::string cp = f.path().string();
    const std::string model = f.attribute_string("/", "model");
    const std::string want = model_key(cfg_.model);
    if (model != want) {
      throw_input_error(fmt::format("{}: a checkpoint of {}, but {} runs {} (case.model = \"{}\")", cp,
                                    model_words(model), cfg_.source_path, model_words(want), want));
    }
    const std::string name = f.attribute_string("/", "case_name");
    if (name != cfg_.name) {
      throw_input_error(fmt::format("{}: the checkpoint is of case '{}' ({}), not of '{}' ({})", cp, name, model,
                                    cfg_.name, want));
    }
    std::vector<CaseDifference> refused;
    for (CaseDifference& d : simulation_differences(f.attribute_string("/", "case_toml"), loaded_.resolved_toml)) {
      if (!allowed_change(d.key, options_.allow_changed)) refused.push_back(std::move(d));
    }
    if (!refused.empty()) {
      std::string more;
      for (std::size_t k = 1; k < refused.size(); ++k) more += (k == 1 ? "" : ", ") + refused[k].key;
      throw_input_error(fmt::format(
          "{}: the case changes {} against the checkpoint ({} there, {} now){}: a restart continues the same "
          "simulation. Restart with the checkpoint's value, or accept the change with --allow-changed {}",
          cp, refused[0].key, refused[0].checkpoint, refused[0].current,
          more.empty() ? "" : fmt::format(" and {} more key{} ({})", refused.size() - 1, refused.size() > 2 ? "s" : "", more),
          refused.size() == 1 ? refused[0].key : refused[0].key + " (once per key, or a whole section)"));
    }
    const double t = f.attribute_double("/", "time");
    if (landed(t)) {
      throw_input_error(fmt::format("{}: the checkpoint is at t = {:.9g} s, at or past the end time {:.9g} s: "
                                    "nothing to run; give a later --end-time", cp, t, cfg_.run.end_time));
    }
  }

  /// Folders, the log and case.toml (rank 0; the other ranks log nothing). A new run does not replace the results
  /// of an earlier one unless asked.
  void prepare_folder() {
    on_root([&] { prepare_folder_here(); });
    if (!root_) log_ptr_ = make_silent_logger();
    threads_ = threads_per_rank();
    omp_set_num_threads(threads_);
    if (comm_.size() > 1) {
      log().info("{} ranks (MPI) x {} thread{} each", comm_.size(), threads_, threads_ == 1 ? "" : "s");
    }
  }

  /// --threads per rank; by default the cores of the machine shared among the ranks it runs (one rank: OpenMP's
  /// default, every core).
  int threads_per_rank() const {
    if (options_.threads > 0) return options_.threads;
    if (comm_.size() == 1) return omp_get_max_threads();
    const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    if (local == nullptr) local = std::getenv("MPI_LOCALNRANKS");
    const int here = local ? std::max(1, std::atoi(local)) : comm_.size();
    return std::max(1, omp_get_num_procs() / here);
  }

  void prepare_folder_here() {
    ensure_directory(out_);
    std::vector<std::string> replaced;
    if (!restart_) {
      replaced = earlier_results(out_);
      if (!replaced.empty() && !options_.overwrite) {
        std::string list;
        for (const auto& r : replaced) list += (list.empty() ? "" : ", ") + r;
        throw_input_error(fmt::format("{} holds the results of an earlier run ({}): choose another --out, continue "
                                      "that run with --restart latest, or replace them with --overwrite",
                                      out_.string(), list));
      }
      for (const char* sub : kResultFolders) fs::remove_all(out_ / sub);
      for (const char* file : kResultFiles) fs::remove(out_ / file);
    }
    for (const char* sub : kResultFolders) ensure_directory(out_ / sub);
    log_ptr_ = make_logger(out_, options_.quiet, restart_);
    log().info("fluidbed run {} -> {}{}", cfg_.source_path, out_.string(),
               restart_ ? " (restart from " + restart_path_.string() + ")" : "");
    for (const std::string& n : cfg_.notes) log().info("note: {}", n);  // what `check` prints: derived defaults
    if (!replaced.empty()) log().warn("--overwrite: replaced the earlier results in {}", out_.string());
    for (const auto& s : skipped_) log().warn("--restart latest: skipped {}", s);
    if (restart_ && options_.restart == "latest") log().info("--restart latest: took {}", restart_path_.string());
    // A stop file that was there before this run started is left from an earlier one: it is not a request to
    // this run.
    std::error_code ec;
    if (fs::remove(out_ / "STOP", ec)) log().warn("removed the stop file {} left from an earlier run", (out_ / "STOP").string());
    if (const int n = remove_stale_temporaries(out_)) {
      log().info("removed {} temporary file{} of a run killed while writing", n, n == 1 ? "" : "s");
    }
  }

  void build_model() {
    try {
      if (cfg_.model == Model::Tfm) {
        model_ = make_tfm_model(cfg_, comm_);
      } else {
        model_ = make_dem_model(cfg_, out_.string(), !restart_, log(), comm_);
      }
    } catch (const Error& e) {
      // The initial gas solve runs here: its failure belongs in log.txt like any other.
      if (e.kind() == ErrorKind::SimulationFailed) log().error("the simulation failed before the first step: {}", e.what());
      throw;
    }
  }

  /// The model, the output schedules and the observers' state: from the checkpoint, or fresh.
  void restore_state() {
    frames_.interval = cfg_.output.interval;
    monitors_.interval = cfg_.output.monitor_interval;
    checkpoints_.interval = cfg_.output.checkpoint_interval;
    probe_rows_.interval = cfg_.probes.interval;
    if (restart_) {
      const Hdf5File& f = *restart_file_;
      model_->load(f);
      frames_.next = f.attribute_int64("/", "next_frame");
      monitors_.next = f.attribute_int64("/", "next_monitor");
      checkpoints_.next = f.attribute_int64("/", "next_checkpoint");
      if (f.has_attribute("/", "next_probe")) {
        probe_rows_.next = f.attribute_int64("/", "next_probe");
      } else if (probe_rows_.interval > 0.0) {  // a checkpoint of a run without probes: the next row after now
        probe_rows_.advance(model_->time(), model_->macro_dt());
      }
      wall_before_ = f.attribute_double("/", "wall_s");
      last_checkpoint_ = restart_path_;
    } else {
      checkpoints_.next = 1;  // none at t = 0
    }
    if (root_) restore_observers();
  }

  /// The observers (rank 0 only: the fields they read are whole on every rank).
  void restore_observers() {
    const FieldView fv = model_->fields();
    // The cell tracers follow the solids field of either dimension.
    const bool moved = fv.has_grid() && fv.has_solids_velocity();
    const bool three_d = fv.dimension == 3;
    if (moved && restart_) {
      // The balls and their colours as saved: recolouring them from the bed at the restart time would move them
      // to other layers.
      if (restart_file_->has("tracers/id")) {
        tracers_.emplace(three_d ? load_tracers<3>(*restart_file_, fv) : load_tracers<2>(*restart_file_, fv));
      } else if (cfg_.output.tracers) {
        log().warn("the checkpoint holds no cell tracers: no tracers/*.csv from this restart");
      }
    } else if (moved && cfg_.output.tracers) {
      // Balls of the paper's Fig. 4b/c over the initial bed.
      tracers_ = three_d ? fresh_tracers<3>(fv, cfg_.particles.layers) : fresh_tracers<2>(fv, cfg_.particles.layers);
      if (!tracers_) log().warn("the initial voidage shows no bed surface: no tracers/*.csv");
    }
    if (tracers_) {
      // Balls cross a periodic side too.
      std::visit([&](auto& t) {
        t.set_periodic(0, cfg_.domain.periodic[0]);
        if (three_d) t.set_periodic(2, cfg_.domain.periodic[2]);
      }, *tracers_);
    }
    if (fv.has_grid() && fv.eps && fv.has_gas_velocity()) {
      bubbles_.emplace(cfg_.bubble);
      if (restart_ && restart_file_->has("bubble/tracked")) bubbles_->restore(load_bubble_state(*restart_file_));
    }
  }

  /// monitor.csv, bubble.csv and the .pvd collections: new, or cut at the restart time and continued (rank 0).
  void open_series() {
    t_start_ = model_->time();
    const std::string description = model_->describe();  // collective: every rank
    if (root_) open_series_here();
    log().info("{}; {} thread{}{}; t = {:.6g} s to {:.6g} s", description, threads_, threads_ == 1 ? "" : "s",
               comm_.size() > 1 ? fmt::format(" per rank, {} ranks", comm_.size()) : "", t_start_, cfg_.run.end_time);
    if (threads_ > 1) {
      const char* note = std::getenv("FLUIDBED_WAIT_NOTE");
      const char* policy = std::getenv("OMP_WAIT_POLICY");
      const char* spin = std::getenv("GOMP_SPINCOUNT");
      log().info("OpenMP waiting: {}", note ? std::string(note)
                                            : fmt::format("OMP_WAIT_POLICY = {}, GOMP_SPINCOUNT = {} (as given)",
                                                          policy ? policy : "unset", spin ? spin : "unset"));
    }
  }

  void open_series_here() {
    // Rows stamped k * interval may lie a rounding above the model time they were written at.
    const double t_cut = t_start_ + kStampTolerance * std::max({cfg_.output.interval, cfg_.output.monitor_interval, 0.0});
    std::vector<std::string> monitor_cols{"time_s"};
    for (auto& c : model_->monitor_columns()) monitor_cols.push_back(c);
    monitor_cols.push_back("wall_s");
    monitor_.emplace(restart_ ? CsvWriter::resume(out_ / "monitor.csv", monitor_cols, t_cut)
                              : CsvWriter(out_ / "monitor.csv", monitor_cols));
    if (bubbles_) {
      std::vector<std::string> cols;
      const std::string header = bubble_csv_header(model_->fields().dimension, true);
      for (std::size_t a = 0, b; a <= header.size(); a = b + 1) {
        b = header.find(',', a);
        if (b == std::string::npos) b = header.size();
        cols.push_back(header.substr(a, b - a));
      }
      bubble_csv_.emplace(restart_ ? CsvWriter::resume(out_ / "bubble.csv", cols, t_cut) : CsvWriter(out_ / "bubble.csv", cols));
      // Every bubble, with the jet bubble's threshold, bed surface and least size (docs/output-format.md).
      const FieldView fv = model_->fields();
      PopulationConfig pc;
      pc.eps_threshold = cfg_.bubble.eps_threshold;
      pc.surface_eps = cfg_.bubble.surface_eps;
      pc.min_size = fv.dimension == 3 ? cfg_.bubble.min_volume : cfg_.bubble.min_area;
      population_.emplace(out_, fv.dimension, pc, restart_, t_cut, restart_ ? &*restart_file_ : nullptr);
      if (restart_ && !restart_file_->has("bubbles/owner")) {
        log().warn("the checkpoint holds no bubble population: bubbles.csv continues with new ids");
      }
    }
    const FieldView fv = model_->fields();
    if (!cfg_.probes.probes.empty()) {
      if (fv.has_grid() && fv.p && fv.eps && fv.has_gas_velocity()) {
        const double t_probe = t_start_ + kStampTolerance * std::max(cfg_.probes.interval, 0.0);
        probes_.emplace(out_ / "probes.csv", cfg_.probes.probes, fv.dimension, fv.has_solids_velocity(), restart_,
                        t_probe);
      } else {
        log().warn("[[probe]] given, but the model has no gas fields: no probes.csv");
      }
    }
    if (cfg_.averages.enabled) {
      if (fv.has_grid() && fv.eps && fv.has_gas_velocity()) {
        averages_.emplace(out_, cfg_.averages, fv, restart_ ? &*restart_file_ : nullptr, t_start_);
        if (restart_ && !averages_->restored()) {
          log().warn("the checkpoint holds no time averages of this window: they start again at t = {:.6g} s", t_start_);
        }
      } else {
        log().warn("[averages] given, but the model has no gas fields: no averages");
      }
    }
    fields_pvd_.emplace(restart_ ? PvdCollection::resume(out_ / "fields.pvd", t_cut) : PvdCollection(out_ / "fields.pvd"));
    particles_pvd_.emplace(restart_ ? PvdCollection::resume(out_ / "particles.pvd", t_cut)
                                    : PvdCollection(out_ / "particles.pvd"));
  }

  void step_until_end() {
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    // Open MPI's mpirun forwards SIGUSR1 to every rank (SIGINT and SIGTERM it turns into a kill after a second):
    // the way to stop a run on several ranks from its launcher, with a checkpoint (docs/parallel.md).
    std::signal(SIGUSR1, on_signal);
    pending_signal.store(0);
    t0_ = std::chrono::steady_clock::now();
    Progress progress(options_.quiet || !root_, t_start_, cfg_.run.end_time);
    dt_ = model_->macro_dt();
    model_steps_before_ = model_->cost().time_steps;  // DEM steps (several per gas step) or TFM steps
    try {
      if (!restart_) observe(model_->time(), step_flags(model_->time()));
      while (!landed(model_->time())) {
        const double t_before = model_->time();
        model_->advance(cfg_.run.end_time);
        inject_fault();
        ++steps_here_;
        const double t = model_->time();
        if (!(t > t_before)) {
          throw_simulation_error(fmt::format("t = {:.9g} s: the model did not advance (internal error)", t));
        }
        const StepFlags flags = step_flags(t);
        model_->share_fields(flags.fields);
        if (tracers_) {
          // The step the model took (the two-fluid model's step is adaptive), not the clock's difference.
          const FieldView fv = model_->fields();
          if (fv.has_solids_velocity()) advance_tracers(*tracers_, fv, model_->last_step());
        }
        observe(t, flags);
        if (checkpoints_.due(t, dt_) && !landed(t)) periodic_checkpoint(t);
        if (stop_requested(flags)) break;
        progress.update(t, steps_here_, wall(), log());
      }
    } catch (const WriteError&) {
      progress.finish();
      throw;
    } catch (const Error& e) {
      progress.finish();
      if (e.kind() == ErrorKind::SimulationFailed) {
        // Every rank stops with the same diagnosis when the failure was found together (a collective test or the
        // same test on the same data); a failure of this rank alone ends the run from main().
        if (!comm_.all_arrive_within(failure_verdict_seconds())) throw;
        save_failed_state(e);
      }
      throw;
    }
    progress.finish();
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    std::signal(SIGUSR1, SIG_DFL);
  }

  /// What every rank decides after a step, taken together (one reduction on several ranks): a stop asked for by a
  /// signal to any rank, by the stop file or the wall-time limit (read by rank 0), whether the time averages
  /// sample now (their observer is rank 0's; the particles they read are gathered from all), whether a probe row
  /// that reads the particles is due (the same), and which of the model's fields rank 0's observers read after
  /// this step.
  struct StepFlags {
    bool signal = false, stop_file = false, wall_limit = false, averages_due = false, particle_probes_due = false;
    FieldNeed fields = FieldNeed::None;
  };
  StepFlags step_flags(double t) {
    double v[6] = {pending_signal.load() != 0 ? 1.0 : 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    if (root_) {
      v[1] = steps_here_ % 64 == 0 && fs::exists(out_ / "STOP") ? 1.0 : 0.0;
      v[2] = cfg_.run.max_wall_time > 0.0 && wall() > cfg_.run.max_wall_time ? 1.0 : 0.0;
      v[3] = averages_ && averages_->samples_at(t, dt_) ? 1.0 : 0.0;
      v[4] = static_cast<double>(fields_read_after_step(t, v[3] != 0.0));
      v[5] = probes_ && probes_->reads_particles() && probe_due(t) ? 1.0 : 0.0;
    }
    if (comm_.size() > 1) comm_.max(std::span<double>(v));
    return {v[0] != 0.0, v[1] != 0.0, v[2] != 0.0, v[3] != 0.0, v[5] != 0.0,
            static_cast<FieldNeed>(static_cast<int>(v[4]))};
  }
  /// Rank 0's observers in observe() and the tracers: every field at a frame (bubbles, field files), a probe row
  /// or an averages sample; the solids velocity alone for the tracers of every step.
  FieldNeed fields_read_after_step(double t, bool averages_due) const {
    if (frames_.due(t, dt_) || (probes_ && probe_due(t)) || averages_due) return FieldNeed::All;
    return tracers_ ? FieldNeed::SolidsVelocity : FieldNeed::None;
  }

  /// A test of the failure paths on several ranks (tests/cli/mpi_faults.sh): FLUIDBED_FAULT="throw RANK STEP"
  /// makes rank RANK alone fail at its step STEP, as a failure no other rank can see would.
  void inject_fault() {
    static const char* fault = std::getenv("FLUIDBED_FAULT");
    if (fault == nullptr) return;
    int rank = -1;
    unsigned long long step = 0;
    if (std::sscanf(fault, "throw %d %llu", &rank, &step) == 2 && rank == comm_.rank() && steps_here_ + 1 == step) {
      throw_simulation_error(fmt::format("t = {:.6g} s: a failure injected on rank {} (FLUIDBED_FAULT)",
                                         model_->time(), rank));
    }
  }

  int finish() {
    const double wall_here = wall();
    const double wall_total = wall_before_ + wall_here;
    if (averages_) averages_->finish();  // a window the run ends inside is written as it stands
    const fs::path final_path = write_checkpoint(stop_reason_.empty() ? "final" : checkpoint_tag(model_->time()), wall_total);
    last_checkpoint_ = final_path;
    const CostInfo cost = model_->cost();  // collective
    const std::string split = model_->parallel_summary();  // collective
    if (!split.empty()) log().info("{}", split);
    const double simulated = model_->time();
    on_root([&] {
      write_file_atomic(out_ / "cost.json",
                        fmt::format("{{\"particles\": {}, \"cells\": {}, \"time_steps\": {}, \"wall_s\": {:.6g}, "
                                    "\"simulated_s\": {:.9g}, \"threads\": {}, \"ranks\": {}, "
                                    "\"wall_per_simulated_s\": {:.6g}}}\n",
                                    cost.particles, cost.cells, cost.time_steps, wall_total, simulated, threads_,
                                    comm_.size(), simulated > 0 ? wall_total / simulated : 0.0));
    });
    const double particle_steps = static_cast<double>(cost.time_steps - model_steps_before_) * static_cast<double>(cost.particles);
    log().info("{} steps in {:.2f} s wall ({:.0f} steps/s{}); checkpoint {}", steps_here_, wall_here,
               steps_here_ / std::max(wall_here, 1e-9),
               cost.particles ? fmt::format(", {} DEM steps, {:.3g} particle-steps/s", cost.time_steps - model_steps_before_,
                                            particle_steps / std::max(wall_here, 1e-9)) : "",
               final_path.string());
    if (!stop_reason_.empty()) {
      log().warn("{}: stopped at t = {:.6g} s; continue with: {}", stop_reason_, model_->time(),
                 continue_command(final_path));
      return 130;
    }
    if (bubbles_) {
      const auto fmt_time = [](std::optional<double> t) { return t ? fmt::format("{:.3f} s", *t) : std::string("none"); };
      // Detachment is from a jet: a bed without one has only eruptions to report.
      if (cfg_.gas.boundary.jets.empty()) {
        log().info("bubble: first eruption {} (no jet: no detachment)", fmt_time(bubbles_->eruption_time()));
      } else {
        log().info("bubble: detachment {}, eruption {}", fmt_time(bubbles_->detachment_time()),
                   fmt_time(bubbles_->eruption_time()));
      }
    }
    log().info("done: t = {:.6g} s; outputs in {}", model_->time(), out_.string());
    return 0;
  }

  // ---- observers ---------------------------------------------------------------------------------------------

  bool probe_due(double t) const { return probe_rows_.interval == 0.0 || probe_rows_.due(t, dt_); }

  /// The outputs due at time t. The model's calls are collective (every rank makes them, in this order); the
  /// observers and writers are rank 0's.
  void observe(double t, const StepFlags& flags) {
    const bool averages_due = flags.averages_due;
    // The particles, gathered once on every rank (collective) for the probes of the particles and the averages
    // that sample now, decided alike on every rank by step_flags.
    const std::optional<ParticleArrays> particles =
        averages_due || flags.particle_probes_due ? model_->particles() : std::nullopt;
    // Probes may sample every step (probes.interval = 0), so before the coarser outputs.
    if (probes_ && probe_due(t)) {
      probes_->sample(probe_rows_.interval == 0.0 ? t : probe_rows_.stamp(t), model_->fields(),
                      flags.particle_probes_due && particles ? &*particles : nullptr);
      probe_rows_.advance(t, dt_);
    }
    if (averages_) averages_->observe(t, dt_, model_->fields(), averages_due ? particles : std::nullopt);
    if (monitors_.due(t, dt_)) {
      std::vector<std::optional<double>> row{monitors_.stamp(t)};
      for (auto& v : model_->monitor_values()) row.push_back(v);
      row.push_back(wall_before_ + wall());
      if (monitor_) monitor_->row(row);
      monitors_.advance(t, dt_);
    }
    if (frames_.due(t, dt_)) {
      const double stamp = frames_.stamp(t);
      if (bubbles_) {
        const FieldView fv = model_->fields();
        BubbleSample b;
        if (fv.dimension == 3) {
          const CellGeometry<3> geo = fv.geometry<3>();
          b = bubbles_->observe<3>(stamp, CellView<3>{geo, fv.eps}, CellView<3>{geo, fv.ug[1]});
        } else {
          const CellGeometry<2> geo = fv.geometry<2>();
          b = bubbles_->observe<2>(stamp, CellView<2>{geo, fv.eps}, CellView<2>{geo, fv.ug[1]});
        }
        const auto values = bubble_csv_values(b, true);
        bubble_csv_->row(std::span<const std::optional<double>>(values.data(), values.size()));
        population_->observe(stamp, fv);
      }
      write_frame(stamp);
      frames_.advance(t, dt_);
    }
  }

  /// Field, particle and tracer files of frame frames_.next, at time `t`.
  void write_frame(double t) {
    const FieldView fv = model_->fields();
    const std::size_t index = static_cast<std::size_t>(frames_.next);
    if (root_ && cfg_.output.fields && fv.has_grid()) {
      const int axes = fv.dimension == 3 ? 3 : 2;
      std::vector<VtiComponents> arrays;
      if (fv.eps) arrays.push_back({"voidage", {fv.eps, nullptr, nullptr}, 1});
      if (fv.p) arrays.push_back({"pressure", {fv.p, nullptr, nullptr}, 1});
      if (fv.has_gas_velocity()) arrays.push_back({"gas_velocity", fv.ug, axes});
      if (fv.has_solids_velocity()) arrays.push_back({"solids_velocity", fv.us, axes});
      if (fv.theta) arrays.push_back({"granular_temperature", {fv.theta, nullptr, nullptr}, 1});
      const std::string rel = frame_file_name("fields", index, "vti");
      write_vti(out_ / rel, VtiGrid{fv.dimension, fv.n, fv.h, fv.origin}, t, arrays);
      fields_pvd_->add(t, rel);
    }
    // Particle frames: every n-th frame (output.particle_interval = n * output.interval, checked by the loader),
    // numbered as the field frame of the same instant.
    const auto every = static_cast<std::size_t>(std::llround(cfg_.output.particle_interval / cfg_.output.interval));
    const bool wanted = cfg_.output.particles || cfg_.output.particles_csv;
    const std::optional<ParticleArrays> p =
        wanted && index % std::max<std::size_t>(every, 1) == 0 ? model_->particles() : std::nullopt;
    if (p && root_) {
      if (cfg_.output.particles) {
        const std::string rel = frame_file_name("particles", index, "vtu");
        write_vtu(out_ / rel, t, *p);
        particles_pvd_->add(t, rel);
      }
      if (cfg_.output.particles_csv) {
        write_particles_csv(out_ / frame_file_name("particles", index, "csv"), *p, Sync::Atomic);
      }
    }
    if (tracers_ && root_) {
      write_file_atomic(out_ / frame_file_name("tracers", index, "csv"), std::visit([](const auto& t) { return tracer_csv(t); }, *tracers_), Sync::Atomic);
    }
  }

  static std::string checkpoint_tag(double t) { return fmt::format("t{:.6f}", t); }

  void periodic_checkpoint(double t) {
    const std::string tag = checkpoint_tag(checkpoints_.stamp(t));
    checkpoints_.advance(t, dt_);
    const fs::path path = write_checkpoint(tag, wall_before_ + wall());
    last_checkpoint_ = path;
    log().info("checkpoint {}", path.string());
    // Older ones go only now that the new one is complete on disk.
    if (!root_) return;
    for (const fs::path& old : rotate_checkpoints(out_ / "checkpoints", path, cfg_.output.checkpoint_keep)) {
      log().info("removed the older checkpoint {} (output.checkpoint_keep = {})", old.string(), cfg_.output.checkpoint_keep);
    }
  }

  /// The whole state of the run: the model, the output schedules, the observers, and the case it belongs to
  /// (a restart refuses a case that changes the simulation).
  fs::path write_checkpoint(const std::string& tag, double wall_total) {
    // One file whatever the number of ranks: the model gathers its state on rank 0, which writes it. A write that
    // fails there fails on every rank, after the gather every rank takes part in.
    const fs::path path = out_ / "checkpoints" / fmt::format("{}.h5", tag);
    std::optional<Hdf5File> f;
    std::optional<WriteError> failed;
    auto attempt = [&](auto&& step) {
      if (!root_ || failed) return;
      try {
        step();
      } catch (const WriteError& e) {
        failed = e;
        f.reset();
      }
    };
    attempt([&] {
      f.emplace(Hdf5File::create(path));
      f->set_attribute("/", "case_name", cfg_.name);
      f->set_attribute("/", "model", model_key(cfg_.model));
      f->set_attribute("/", "case_toml", loaded_.resolved_toml);
      f->set_attribute("/", "time", model_->time());
      f->set_attribute("/", "seed", static_cast<std::int64_t>(cfg_.seed));
      f->set_attribute("/", "next_frame", frames_.next);
      f->set_attribute("/", "next_monitor", monitors_.next);
      f->set_attribute("/", "next_checkpoint", checkpoints_.next);
      f->set_attribute("/", "next_probe", probe_rows_.next);
      f->set_attribute("/", "wall_s", wall_total);
      f->set_attribute("/", "ranks", static_cast<std::int64_t>(comm_.size()));
    });
    model_->save(f ? &*f : nullptr);
    attempt([&] {
      if (bubbles_) save_bubble_state(*f, bubbles_->state());
      if (population_) population_->save(*f);
      if (averages_) averages_->save(*f);
      if (tracers_) save_tracers(*f, *tracers_);
      f->commit();
    });
    if (comm_.size() > 1) {
      Bytes verdict;
      if (failed) {
        const std::string m = failed->what();
        pack(verdict, failed->error_number());
        verdict.insert(verdict.end(), reinterpret_cast<const std::byte*>(m.data()),
                       reinterpret_cast<const std::byte*>(m.data()) + m.size());
      }
      comm_.broadcast(verdict, 0);
      if (!verdict.empty() && !failed) {
        Unpacker u(verdict);
        const int err = u.get<int>();
        failed.emplace(path, std::string(reinterpret_cast<const char*>(verdict.data()) + sizeof(int),
                                         verdict.size() - sizeof(int)), err);
      }
    }
    if (failed) throw *failed;
    return path;
  }

  /// A failed simulation keeps its last state for inspection (and a restart with changed settings).
  void save_failed_state(const Error& e) {
    try {
      const fs::path path = write_checkpoint(fmt::format("failed-t{:.6f}", model_->time()), wall_before_ + wall());
      log().error("the simulation failed: {}", e.what());
      log().error("last state saved to {}", path.string());
    } catch (const std::exception& inner) {
      log().error("the simulation failed: {} (and the final checkpoint could not be written: {})", e.what(), inner.what());
    }
  }

  /// A write that failed (disk full, quota, I/O error) ends the run as a failure: nothing more is written, the
  /// last complete checkpoint is the place to continue from.
  [[noreturn]] void output_failed(const WriteError& e) {
    const double t = model_ ? model_->time() : 0.0;
    std::error_code ec;
    const auto last_size = last_checkpoint_.empty() ? 0 : fs::file_size(last_checkpoint_, ec);
    const std::string size_hint =
        e.path().parent_path().filename() == "checkpoints" && !ec && last_size > 0
            ? fmt::format(" (a checkpoint takes about {:.3g} MB: the last one)", static_cast<double>(last_size) / 1e6)
            : "";
    std::string resume = last_checkpoint_.empty()
                             ? std::string("no checkpoint was written yet, so the run must start again (a shorter "
                                           "output.checkpoint_interval loses less)")
                             : fmt::format("the last complete checkpoint is {}; continue with: {}", last_checkpoint_.string(),
                                           continue_command(last_checkpoint_));
    const std::string message =
        fmt::format("t = {:.6g} s: an output could not be written: {}{}. Every file under its final name is whole; "
                    "{}. Likely cause: the disk or quota is full; remedy: free space (or choose another --out) and "
                    "continue.", t, e.what(), size_hint, resume);
    if (log_ptr_) log().error("the simulation failed: {}", message);
    throw_simulation_error(message);
  }

  // ---- helpers -----------------------------------------------------------------------------------------------

  /// The model is at the end time, up to a rounding far below one step.
  bool landed(double t) const {
    const double tol = dt_ > 0.0 ? 1e-3 * dt_ : 1e-12 * std::max(1.0, std::abs(cfg_.run.end_time));
    return t >= cfg_.run.end_time - tol;
  }

  bool stop_requested(const StepFlags& flags) {
    if (flags.signal) {
      // The signal as this rank saw it, or a stop that another rank's signal asked for.
      const int sig = pending_signal.load();
      stop_reason_ = sig == SIGINT    ? "interrupted (SIGINT)"
                     : sig == SIGTERM ? "terminated (SIGTERM)"
                     : sig == SIGUSR1 ? "stop asked for (SIGUSR1)"
                                      : "interrupted (a signal to another rank)";
    } else if (flags.stop_file) {
      stop_reason_ = "stop file " + (out_ / "STOP").string() + " found";
      if (root_) fs::remove(out_ / "STOP");
    } else if (flags.wall_limit) {
      stop_reason_ = fmt::format("wall-time limit of {} s reached", cfg_.run.max_wall_time);
    }
    return !stop_reason_.empty();
  }

  /// The command that continues this run exactly: the same case file, folder, end time, overrides and
  /// options, from `checkpoint`.
  std::string continue_command(const fs::path& checkpoint) const {
    // On several ranks the same launcher line (any number of ranks continues the run: docs/parallel.md).
    std::string cmd = (comm_.size() > 1 ? fmt::format("mpirun -n {} ", comm_.size()) : std::string()) + "fluidbed run " +
                      shell_word(cfg_.source_path) + " --out " + shell_word(out_.string());
    if (options_.end_time) cmd += fmt::format(" --end-time {}", *options_.end_time);
    for (const std::string& s : options_.sets) cmd += " --set " + shell_word(s);
    for (const std::string& a : options_.allow_changed) cmd += " --allow-changed " + shell_word(a);
    if (options_.threads > 0) cmd += fmt::format(" --threads {}", options_.threads);
    if (options_.max_wall_time) cmd += fmt::format(" --max-wall-time {}", *options_.max_wall_time);
    if (options_.quiet) cmd += " --quiet";
    return cmd + " --restart " + shell_word(checkpoint.string());
  }

  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count(); }
  spdlog::logger& log() { return *log_ptr_; }

  /// Runs f on rank 0; an error it raises is raised on every rank (the others wait for the verdict), so that a
  /// refusal (a folder in use, results to keep, a bad checkpoint) ends every rank the same way.
  template <class F>
  void on_root(F&& f) {
    if (comm_.size() == 1) {
      f();
      return;
    }
    Bytes verdict;
    if (root_) {
      try {
        f();
      } catch (const WriteError& e) {
        pack(verdict, std::uint8_t{2});
        pack(verdict, static_cast<int>(e.kind()));
        append_text(verdict, e.what());
      } catch (const Error& e) {
        pack(verdict, std::uint8_t{1});
        pack(verdict, static_cast<int>(e.kind()));
        append_text(verdict, e.what());
      }
    }
    comm_.broadcast(verdict, 0);
    if (verdict.empty()) return;
    Unpacker u(verdict);
    const auto what = u.get<std::uint8_t>();
    const auto kind = static_cast<ErrorKind>(u.get<int>());
    const std::string msg(reinterpret_cast<const char*>(verdict.data()) + 1 + sizeof(int), verdict.size() - 1 - sizeof(int));
    if (what == 2) throw WriteError(out_, msg);
    throw Error(kind, msg);
  }
  static void append_text(Bytes& b, const std::string& s) {
    b.insert(b.end(), reinterpret_cast<const std::byte*>(s.data()), reinterpret_cast<const std::byte*>(s.data()) + s.size());
  }

  const LoadedCase& loaded_;
  const RunOptions& options_;
  const Comm& comm_;
  bool root_;
  CaseConfig cfg_;
  bool restart_;
  fs::path out_;
  fs::path restart_path_;
  std::optional<Hdf5File> restart_file_;
  std::vector<std::string> skipped_;
  std::shared_ptr<spdlog::logger> log_ptr_;
  int threads_ = 1;

  std::unique_ptr<ModelRun> model_;
  Schedule frames_, monitors_, checkpoints_, probe_rows_;
  std::optional<TracerBalls> tracers_;
  std::optional<BubbleTracker> bubbles_;
  std::optional<BubbleSeries> population_;
  std::optional<ProbeSeries> probes_;
  std::optional<AverageSeries> averages_;
  std::optional<CsvWriter> monitor_, bubble_csv_;
  std::optional<PvdCollection> fields_pvd_, particles_pvd_;
  fs::path last_checkpoint_;

  std::chrono::steady_clock::time_point t0_ = std::chrono::steady_clock::now();
  double wall_before_ = 0.0, t_start_ = 0.0, dt_ = 0.0;
  std::uint64_t steps_here_ = 0, model_steps_before_ = 0;
  std::string stop_reason_;
};

}  // namespace

int run_case(const LoadedCase& loaded, const RunOptions& options) { return Run(loaded, options).execute(); }

double failure_verdict_seconds() {
  const char* v = std::getenv("FLUIDBED_FAILURE_WAIT");
  const double s = v ? std::atof(v) : 0.0;
  return s > 0.0 ? s : 30.0;
}

}  // namespace fluidbed
