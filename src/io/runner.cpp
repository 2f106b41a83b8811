#include "io/runner.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <limits>
#include <span>
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>
#include <unistd.h>

#include "analysis/bed_surface.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/layer_tracers.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/dem_model.hpp"
#include "io/tfm_model.hpp"
#include "io/hdf5_file.hpp"
#include "io/pvd.hpp"
#include "io/vtk_writer.hpp"

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

/// Scheduled output: the k-th event is due at k * interval.
struct Schedule {
  double interval = 0.0;
  std::int64_t next = 0;
  bool due(double t, double dt) const { return interval > 0.0 && t >= next * interval - slack(dt); }
  void advance(double t, double dt) {
    while (interval > 0.0 && t >= next * interval - slack(dt)) ++next;
  }
  double slack(double dt) const { return std::max(0.5 * dt, 1e-9 * interval); }
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
  return s;
}

}  // namespace

int run_case(const LoadedCase& loaded, const RunOptions& options) {
  CaseConfig cfg = loaded.config;
  if (options.end_time) cfg.run.end_time = *options.end_time;
  if (options.max_wall_time) cfg.run.max_wall_time = *options.max_wall_time;
  const fs::path out = options.out_dir.empty() ? fs::path("out") / cfg.name : fs::path(options.out_dir);
  const bool restart = !options.restart.empty();

  ensure_directory(out);
  if (!restart) {
    for (const char* sub : {"fields", "particles", "tracers", "checkpoints"}) fs::remove_all(out / sub);
    for (const char* file : {"fields.pvd", "particles.pvd", "monitor.csv", "bubble.csv", "cost.json"}) fs::remove(out / file);
  }
  for (const char* sub : {"fields", "particles", "tracers", "checkpoints"}) ensure_directory(out / sub);
  auto log_ptr = make_logger(out, options.quiet, restart);
  spdlog::logger& log = *log_ptr;
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const int threads = omp_get_max_threads();

  // The resolved case (with command-line overrides) makes any run repeatable.
  write_file_atomic(out / "case.toml", loaded.resolved_toml);
  log.info("fluidbed run {} -> {}{}", cfg.source_path, out.string(), restart ? " (restart from " + options.restart + ")" : "");

  std::unique_ptr<ModelRun> model;
  std::optional<Hdf5File> restart_file;
  if (restart) {
    if (!fs::exists(options.restart)) throw_input_error(fmt::format("{}: restart file not found", options.restart));
    restart_file.emplace(Hdf5File::open(options.restart));
    const std::string name = restart_file->attribute_string("/", "case_name");
    const std::string model_name = restart_file->attribute_string("/", "model");
    const std::string want_model = cfg.model == Model::Tfm ? "tfm" : "dem";
    if (name != cfg.name || model_name != want_model) {
      throw_input_error(fmt::format("{}: the checkpoint is of case '{}' ({}), not of '{}' ({})", options.restart, name,
                                    model_name, cfg.name, want_model));
    }
  }
  try {
    if (cfg.model == Model::Tfm) {
      model = make_tfm_model(cfg);
    } else {
      model = make_dem_model(cfg, out.string(), !restart, log);
    }
  } catch (const Error& e) {
    // The initial gas solve runs here: its failure belongs in log.txt like any other.
    if (e.kind() == ErrorKind::SimulationFailed) log.error("the simulation failed before the first step: {}", e.what());
    throw;
  }

  // Observers.
  Schedule frames{cfg.output.interval}, monitors{cfg.output.monitor_interval}, checkpoints{cfg.output.checkpoint_interval};
  double wall_before = 0.0;
  std::optional<CellTracers> tracers;
  std::optional<BubbleTracker> bubbles;
  if (restart) {
    model->load(*restart_file);
    frames.next = restart_file->attribute_int64("/", "next_frame");
    monitors.next = restart_file->attribute_int64("/", "next_monitor");
    checkpoints.next = restart_file->attribute_int64("/", "next_checkpoint");
    wall_before = restart_file->attribute_double("/", "wall_s");
  } else {
    checkpoints.next = 1;  // none at t = 0
  }
  const FieldView fv0 = model->fields();
  if (fv0.grid && cfg.output.tracers) {
    // Balls of the paper's Fig. 4b/c over the initial bed.
    const double h = fv0.eps ? bed_surface_height(*fv0.grid, *fv0.eps).value_or(0.0) : 0.0;
    if (h > 0.0) tracers.emplace(*fv0.grid, h, cfg.particles.layers);
  }
  if (restart && tracers && restart_file->has("tracers/x")) {
    tracers->x = restart_file->read_double("tracers/x");
    tracers->y = restart_file->read_double("tracers/y");
  }
  if (fv0.grid && fv0.eps && fv0.ug && fv0.vg) {
    bubbles.emplace(cfg.bubble);
    if (restart && restart_file->has("bubble/tracked")) bubbles->restore(load_bubble_state(*restart_file));
  }
  restart_file.reset();

  const double t_restart = model->time();
  std::vector<std::string> monitor_cols{"time_s"};
  for (auto& c : model->monitor_columns()) monitor_cols.push_back(c);
  monitor_cols.push_back("wall_s");
  CsvWriter monitor = restart ? CsvWriter::resume(out / "monitor.csv", monitor_cols, t_restart)
                              : CsvWriter(out / "monitor.csv", monitor_cols);
  std::optional<CsvWriter> bubble_csv;
  if (bubbles) {
    std::vector<std::string> cols;
    std::string header = bubble_csv_header();
    for (std::size_t a = 0, b; a <= header.size(); a = b + 1) {
      b = header.find(',', a);
      if (b == std::string::npos) b = header.size();
      cols.push_back(header.substr(a, b - a));
    }
    bubble_csv.emplace(restart ? CsvWriter::resume(out / "bubble.csv", cols, t_restart) : CsvWriter(out / "bubble.csv", cols));
  }
  PvdCollection fields_pvd = restart ? PvdCollection::resume(out / "fields.pvd", t_restart) : PvdCollection(out / "fields.pvd");
  PvdCollection particles_pvd =
      restart ? PvdCollection::resume(out / "particles.pvd", t_restart) : PvdCollection(out / "particles.pvd");

  log.info("{}; {} thread{}; t = {:.6g} s to {:.6g} s", model->describe(), threads, threads == 1 ? "" : "s", t_restart,
           cfg.run.end_time);

  auto write_frame = [&](double t) {
    const FieldView fv = model->fields();
    const std::size_t index = static_cast<std::size_t>(frames.next);
    if (cfg.output.fields && fv.grid) {
      std::vector<VtiArray> arrays;
      if (fv.eps) arrays.push_back(VtiArray::scalar("voidage", *fv.eps));
      if (fv.p) arrays.push_back(VtiArray::scalar("pressure", *fv.p));
      if (fv.ug && fv.vg) arrays.push_back(VtiArray::vector("gas_velocity", *fv.ug, *fv.vg));
      if (fv.us && fv.vs) arrays.push_back(VtiArray::vector("solids_velocity", *fv.us, *fv.vs));
      if (fv.theta) arrays.push_back(VtiArray::scalar("granular_temperature", *fv.theta));
      const std::string rel = frame_file_name("fields", index, "vti");
      write_vti(out / rel, *fv.grid, t, arrays);
      fields_pvd.add(t, rel);
    }
    if (const ParticleStore* p = model->particles()) {
      if (cfg.output.particles) {
        const std::string rel = frame_file_name("particles", index, "vtu");
        write_vtu(out / rel, t, *p);
        particles_pvd.add(t, rel);
      }
      if (cfg.output.particles_csv) {
        write_particles_csv(out / frame_file_name("particles", index, "csv"), *p, Sync::Atomic);
      }
    }
    if (tracers) {
      write_file_atomic(out / frame_file_name("tracers", index, "csv"), tracer_csv(*tracers), Sync::Atomic);
    }
  };

  auto write_checkpoint = [&](const std::string& tag, double wall_total) {
    const fs::path path = out / "checkpoints" / fmt::format("{}.h5", tag);
    Hdf5File f = Hdf5File::create(path);
    f.set_attribute("/", "case_name", cfg.name);
    f.set_attribute("/", "model", cfg.model == Model::Tfm ? "tfm" : "dem");
    f.set_attribute("/", "time", model->time());
    f.set_attribute("/", "seed", static_cast<std::int64_t>(cfg.seed));
    f.set_attribute("/", "next_frame", frames.next);
    f.set_attribute("/", "next_monitor", monitors.next);
    f.set_attribute("/", "next_checkpoint", checkpoints.next);
    f.set_attribute("/", "wall_s", wall_total);
    model->save(f);
    if (bubbles) save_bubble_state(f, bubbles->state());
    if (tracers) {
      f.create_group("tracers");
      f.write("tracers/x", tracers->x);
      f.write("tracers/y", tracers->y);
    }
    f.commit();
    return path;
  };

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  pending_signal.store(0);

  const auto t0 = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  Progress progress(options.quiet, t_restart, cfg.run.end_time);
  const double dt = model->macro_dt();
  std::uint64_t steps_here = 0;
  const std::uint64_t model_steps_before = model->cost().time_steps;  // DEM steps (several per gas step) or TFM steps
  std::string stop_reason;

  auto observe = [&](double t) {
    if (monitors.due(t, dt)) {
      std::vector<std::optional<double>> row{t};
      for (auto& v : model->monitor_values()) row.push_back(v);
      row.push_back(wall_before + wall());
      monitor.row(row);
      monitors.advance(t, dt);
    }
    if (frames.due(t, dt)) {
      if (bubbles) {
        const FieldView fv = model->fields();
        const BubbleSample b = bubbles->observe(t, *fv.grid, *fv.eps, *fv.ug, *fv.vg);
        const auto values = bubble_csv_values(b);
        bubble_csv->row(std::span<const std::optional<double>>(values.data(), values.size()));
      }
      write_frame(t);
      frames.advance(t, dt);
    }
  };

  try {
    if (!restart) observe(model->time());
    while (model->time() < cfg.run.end_time - 0.5 * dt) {
      const double t_before = model->time();
      model->advance(cfg.run.end_time);
      ++steps_here;
      const double t = model->time();
      if (tracers) {
        // The step actually taken: the two-fluid model's step is adaptive.
        const FieldView fv = model->fields();
        if (fv.us && fv.vs) tracers->advance(*fv.us, *fv.vs, t - t_before);
      }
      observe(t);
      if (checkpoints.due(t, dt) && t < cfg.run.end_time - 0.5 * dt) {
        checkpoints.advance(t, dt);
        const auto path = write_checkpoint(fmt::format("t{:.6f}", t), wall_before + wall());
        log.info("checkpoint {}", path.string());
      }
      if (pending_signal.load() != 0) {
        stop_reason = pending_signal.load() == SIGINT ? "interrupted (SIGINT)" : "terminated (SIGTERM)";
      } else if (steps_here % 64 == 0 && fs::exists(out / "STOP")) {
        stop_reason = "stop file " + (out / "STOP").string() + " found";
        fs::remove(out / "STOP");
      } else if (cfg.run.max_wall_time > 0.0 && wall() > cfg.run.max_wall_time) {
        stop_reason = fmt::format("wall-time limit of {} s reached", cfg.run.max_wall_time);
      }
      if (!stop_reason.empty()) break;
      progress.update(t, steps_here, wall(), log);
    }
  } catch (const Error& e) {
    progress.finish();
    if (e.kind() == ErrorKind::SimulationFailed) {
      try {
        const auto path = write_checkpoint(fmt::format("failed-t{:.6f}", model->time()), wall_before + wall());
        log.error("the simulation failed: {}", e.what());
        log.error("last state saved to {}", path.string());
      } catch (const std::exception& inner) {
        log.error("the simulation failed: {} (and the final checkpoint could not be written: {})", e.what(), inner.what());
      }
    }
    throw;
  }
  progress.finish();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);

  const double wall_here = wall();
  wall_before += wall_here;
  const auto final_path =
      write_checkpoint(stop_reason.empty() ? "final" : fmt::format("t{:.6f}", model->time()), wall_before);
  const CostInfo cost = model->cost();
  const double simulated = model->time();
  write_file_atomic(out / "cost.json",
                    fmt::format("{{\"particles\": {}, \"cells\": {}, \"time_steps\": {}, \"wall_s\": {:.6g}, "
                                "\"simulated_s\": {:.9g}, \"threads\": {}, \"wall_per_simulated_s\": {:.6g}}}\n",
                                cost.particles, cost.cells, cost.time_steps, wall_before, simulated, threads,
                                simulated > 0 ? wall_before / simulated : 0.0));
  const double particle_steps = static_cast<double>(cost.time_steps - model_steps_before) * static_cast<double>(cost.particles);
  log.info("{} steps in {:.2f} s wall ({:.0f} steps/s{}); checkpoint {}", steps_here, wall_here,
           steps_here / std::max(wall_here, 1e-9),
           cost.particles ? fmt::format(", {} DEM steps, {:.3g} particle-steps/s", cost.time_steps - model_steps_before,
                                        particle_steps / std::max(wall_here, 1e-9)) : "",
           final_path.string());
  if (!stop_reason.empty()) {
    log.warn("{}: stopped at t = {:.6g} s; continue with: fluidbed run {} --out {} --restart {}", stop_reason,
             model->time(), cfg.source_path, out.string(), final_path.string());
    return 130;
  }
  if (bubbles) {
    const auto fmt_time = [](std::optional<double> t) { return t ? fmt::format("{:.3f} s", *t) : std::string("none"); };
    log.info("bubble: detachment {}, eruption {}", fmt_time(bubbles->detachment_time()),
             fmt_time(bubbles->eruption_time()));
  }
  log.info("done: t = {:.6g} s; outputs in {}", model->time(), out.string());
  return 0;
}

}  // namespace fluidbed
