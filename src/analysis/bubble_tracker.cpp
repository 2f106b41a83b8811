#include "analysis/bubble_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "analysis/bed_surface.hpp"
#include "core/error.hpp"

namespace fluidbed {

double threshold_crossing(double y_lo, double eps_lo, double y_hi, double eps_hi, double threshold) {
  const double d = eps_lo - eps_hi;
  if (d == 0.0) return y_hi;
  const double s = std::clamp((eps_lo - threshold) / d, 0.0, 1.0);
  return y_lo + s * (y_hi - y_lo);
}

double interpolate_cell_centred(const Grid2& grid, const Field2& f, double x, double y) {
  // Position in units of cells measured from the first cell centre; clamped so the stencil stays on the grid.
  const double sx = std::clamp((x - grid.x0) / grid.dx - 0.5, 0.0, static_cast<double>(grid.nx - 1));
  const double sy = std::clamp((y - grid.y0) / grid.dy - 0.5, 0.0, static_cast<double>(grid.ny - 1));
  const int i0 = std::min(static_cast<int>(sx), grid.nx - 1);
  const int j0 = std::min(static_cast<int>(sy), grid.ny - 1);
  const int i1 = std::min(i0 + 1, grid.nx - 1);
  const int j1 = std::min(j0 + 1, grid.ny - 1);
  const double wx = sx - i0;
  const double wy = sy - j0;
  return (1.0 - wy) * ((1.0 - wx) * f(i0, j0) + wx * f(i1, j0)) + wy * ((1.0 - wx) * f(i0, j1) + wx * f(i1, j1));
}

int label_regions(int nx, int ny, const std::vector<std::uint8_t>& mask, std::vector<int>& label) {
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  label.assign(n, -1);
  std::vector<std::size_t> stack;
  int count = 0;
  for (std::size_t start = 0; start < n; ++start) {
    if (!mask[start] || label[start] >= 0) continue;
    label[start] = count;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const int i = static_cast<int>(k % static_cast<std::size_t>(nx));
      const int j = static_cast<int>(k / static_cast<std::size_t>(nx));
      const auto visit = [&](int ii, int jj) {
        if (ii < 0 || ii >= nx || jj < 0 || jj >= ny) return;
        const std::size_t kk = static_cast<std::size_t>(jj) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ii);
        if (mask[kk] && label[kk] < 0) {
          label[kk] = count;
          stack.push_back(kk);
        }
      };
      visit(i - 1, j);
      visit(i + 1, j);
      visit(i, j - 1);
      visit(i, j + 1);
    }
    ++count;
  }
  return count;
}

BubbleTracker::BubbleTracker(const BubbleConfig& config) : config_(config) {
  if (!(config_.eps_threshold > 0.0 && config_.eps_threshold < 1.0))
    throw_input_error(fmt::format("bubble threshold voidage must lie in (0, 1), got {}", config_.eps_threshold));
  if (!(config_.u_mf > 0.0)) throw_input_error(fmt::format("bubble u_mf must be positive, got {}", config_.u_mf));
  if (!(config_.jet_width >= 0.0)) throw_input_error("bubble jet width must not be negative");
  if (config_.rise_velocity_samples < 2) throw_input_error("bubble rise_velocity_samples must be at least 2");
}

namespace {

struct RegionStats {
  std::size_t cells = 0;
  bool freeboard = false;
  bool attached = false;
  double sum_x = 0.0, sum_y = 0.0;
  int top_i = -1, top_j = -1;
};

void check_field(const Grid2& grid, const Field2& f, const char* name) {
  if (f.nx != grid.nx || f.ny != grid.ny || f.size() != grid.cells())
    throw_input_error(fmt::format("bubble tracker: field {} is {}x{}, the grid {}x{}", name, f.nx, f.ny, grid.nx,
                                  grid.ny));
}

// Least-squares slope of h(t); exact for a nose moving at constant speed.
double lsq_slope(const std::vector<double>& t, const std::vector<double>& h) {
  const double n = static_cast<double>(t.size());
  double tm = 0.0, hm = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    tm += t[k];
    hm += h[k];
  }
  tm /= n;
  hm /= n;
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    num += (t[k] - tm) * (h[k] - hm);
    den += (t[k] - tm) * (t[k] - tm);
  }
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace

BubbleSample BubbleTracker::observe(double t, const Grid2& grid, const Field2& eps, const Field2& ug_cc,
                                    const Field2& vg_cc) {
  if (config_.grid.nx > 0 && (config_.grid.nx != grid.nx || config_.grid.ny != grid.ny))
    throw_input_error(fmt::format("bubble tracker: configured for a {}x{} grid, given {}x{}", config_.grid.nx,
                                  config_.grid.ny, grid.nx, grid.ny));
  check_field(grid, eps, "eps");
  check_field(grid, ug_cc, "ug");
  check_field(grid, vg_cc, "vg");
  const int nx = grid.nx;
  const int ny = grid.ny;
  const double thr = config_.eps_threshold;

  BubbleSample s;
  s.time = t;

  // Bed surface: highest row whose mean voidage is still that of a bed; rows above it are freeboard.
  const int j_surf = bed_surface_row(grid, eps, config_.surface_eps);
  if (j_surf >= 0) s.bed_height = grid.y0 + (j_surf + 1) * grid.dy;

  std::vector<std::uint8_t> mask(grid.cells());
  for (std::size_t k = 0; k < mask.size(); ++k) mask[k] = eps.v[k] > thr ? 1 : 0;
  std::vector<int> label;
  const int n_regions = label_regions(nx, ny, mask, label);

  // Bottom cells "above the jet": every column whose span overlaps the jet opening, at least the one holding jet_x.
  const double jet_lo = config_.jet_x - 0.5 * config_.jet_width;
  const double jet_hi = config_.jet_x + 0.5 * config_.jet_width;
  std::vector<std::uint8_t> jet_column(static_cast<std::size_t>(nx), 0);
  for (int i = 0; i < nx; ++i) {
    const double a = grid.x0 + i * grid.dx;
    const double b = a + grid.dx;
    if (std::min(b, jet_hi) - std::max(a, jet_lo) > 1e-9 * grid.dx) jet_column[static_cast<std::size_t>(i)] = 1;
  }
  jet_column[static_cast<std::size_t>(grid.cell_i(config_.jet_x))] = 1;

  std::vector<RegionStats> region(static_cast<std::size_t>(n_regions));
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int l = label[grid.index(i, j)];
      if (l < 0) continue;
      RegionStats& r = region[static_cast<std::size_t>(l)];
      ++r.cells;
      r.sum_x += grid.xc(i);
      r.sum_y += grid.yc(j);
      if (j_surf < 0 || j > j_surf) r.freeboard = true;
      if (j == 0 && jet_column[static_cast<std::size_t>(i)]) r.attached = true;
      const bool closer = r.top_j == j && std::abs(grid.xc(i) - config_.jet_x) < std::abs(grid.xc(r.top_i) - config_.jet_x);
      if (j > r.top_j || closer) {
        r.top_i = i;
        r.top_j = j;
      }
    }
  }
  const double cell_area = grid.dx * grid.dy;
  const auto is_candidate = [&](int l) {
    const RegionStats& r = region[static_cast<std::size_t>(l)];
    return !r.freeboard && static_cast<double>(r.cells) * cell_area >= config_.min_area;
  };

  int chosen = -1;
  if (tracking_) {
    // The tracked bubble is the region sharing most cells with it at the previous sample.
    std::vector<std::size_t> overlap(static_cast<std::size_t>(n_regions), 0);
    if (tracked_.size() == label.size()) {
      for (std::size_t k = 0; k < label.size(); ++k)
        if (tracked_[k] && label[k] >= 0) ++overlap[static_cast<std::size_t>(label[k])];
    }
    std::size_t best = 0, free_overlap = 0;
    for (int l = 0; l < n_regions; ++l) {
      const std::size_t o = overlap[static_cast<std::size_t>(l)];
      if (region[static_cast<std::size_t>(l)].freeboard) {
        free_overlap += o;
      } else if (is_candidate(l) && o > best) {
        best = o;
        chosen = l;
      }
    }
    if (chosen >= 0 && free_overlap > best) chosen = -1;
    if (chosen < 0) {
      tracking_ = false;
      if (free_overlap > 0) {
        s.erupted = true;
        if (!eruption_time_) eruption_time_ = t;
      }
    }
  }
  if (!tracking_ && !s.erupted) {
    // A new bubble: the one on the jet if there is one, else the largest void in the bed.
    std::size_t best = 0;
    bool best_attached = false;
    for (int l = 0; l < n_regions; ++l) {
      if (!is_candidate(l)) continue;
      const RegionStats& r = region[static_cast<std::size_t>(l)];
      if ((r.attached && !best_attached) || (r.attached == best_attached && r.cells > best)) {
        best = r.cells;
        best_attached = r.attached;
        chosen = l;
      }
    }
    if (chosen >= 0) {
      tracking_ = true;
      was_attached_ = false;
      nose_t_.clear();
      nose_h_.clear();
      ++bubble_count_;
    }
  }
  if (chosen < 0) {
    tracked_.clear();
    return s;
  }

  const RegionStats& r = region[static_cast<std::size_t>(chosen)];
  s.bubble_id = bubble_count_ - 1;
  s.area = static_cast<double>(r.cells) * cell_area;
  s.equivalent_diameter = std::sqrt(4.0 * *s.area / std::numbers::pi);
  s.centroid_x = r.sum_x / static_cast<double>(r.cells);
  s.centroid_y = r.sum_y / static_cast<double>(r.cells);
  s.attached = r.attached;
  if (was_attached_ && !r.attached) {
    s.detached = true;
    if (!detachment_time_) detachment_time_ = t;
  }
  was_attached_ = r.attached;

  // Nose: top of the bubble on the vertical line x = jet_x, eps linearly interpolated between the two nearest
  // columns of cell centres; if the bubble has drifted off that line, on the column of its highest cell.
  const double sx = (config_.jet_x - grid.x0) / grid.dx - 0.5;
  int i0 = static_cast<int>(std::floor(sx));
  double wx = sx - i0;
  if (i0 < 0) {
    i0 = 0;
    wx = 0.0;
  } else if (i0 >= nx - 1) {
    i0 = nx - 1;
    wx = 0.0;
  }
  const int i1 = std::min(i0 + 1, nx - 1);
  const auto line_eps = [&](int j) { return (1.0 - wx) * eps(i0, j) + wx * eps(i1, j); };
  int j_top = -1;
  for (int j = ny - 1; j >= 0 && j_top < 0; --j) {
    const bool in_bubble = label[grid.index(i0, j)] == chosen || (wx > 0.0 && label[grid.index(i1, j)] == chosen);
    if (in_bubble && line_eps(j) > thr) j_top = j;
  }
  double nose = 0.0;
  if (j_top >= 0) {
    s.nose_x = config_.jet_x;
    nose = (j_top + 1 < ny && line_eps(j_top + 1) <= thr)
               ? threshold_crossing(grid.yc(j_top), line_eps(j_top), grid.yc(j_top + 1), line_eps(j_top + 1), thr)
               : grid.y0 + (j_top + 1) * grid.dy;
  } else {
    const int it = r.top_i;
    const int jt = r.top_j;
    s.nose_x = grid.xc(it);
    nose = (jt + 1 < ny) ? threshold_crossing(grid.yc(jt), eps(it, jt), grid.yc(jt + 1), eps(it, jt + 1), thr)
                         : grid.y0 + (jt + 1) * grid.dy;
  }
  s.nose_height = nose;

  // Rise velocity: least-squares slope of the nose height over the last rise_velocity_samples samples.
  nose_t_.push_back(t);
  nose_h_.push_back(nose);
  const std::size_t keep = static_cast<std::size_t>(config_.rise_velocity_samples);
  if (nose_t_.size() > keep) {
    nose_t_.erase(nose_t_.begin());
    nose_h_.erase(nose_h_.begin());
  }
  if (nose_t_.size() >= 2) s.rise_velocity = lsq_slope(nose_t_, nose_h_);

  // Axial interstitial gas velocity in the emulsion just above the roof: half a cell above the nose.
  s.nose_gas_velocity = interpolate_cell_centred(grid, vg_cc, *s.nose_x, nose + 0.5 * grid.dy);
  // Throughflow relative to the rising nose, in units of U_mf (Table 2).
  if (s.rise_velocity) s.throughflow_ratio = (*s.nose_gas_velocity - *s.rise_velocity) / config_.u_mf;

  tracked_.assign(label.size(), 0);
  for (std::size_t k = 0; k < label.size(); ++k) tracked_[k] = label[k] == chosen ? 1 : 0;
  return s;
}

namespace {

std::string opt(const std::optional<double>& v) { return v ? fmt::format("{}", *v) : std::string(); }

}  // namespace

std::string bubble_csv_header() {
  return "time_s,nose_height_m,rise_velocity_m_s,nose_gas_velocity_m_s,throughflow_ratio,bubble_area_m2,attached,"
         "equivalent_diameter_m,bed_height_m,erupted,bubble_id,nose_x_m";
}

std::vector<std::optional<double>> bubble_csv_values(const BubbleSample& s) {
  std::optional<double> attached;
  if (s.attached) attached = *s.attached ? 1.0 : 0.0;
  std::optional<double> id;
  if (s.bubble_id >= 0) id = static_cast<double>(s.bubble_id);
  return {s.time, s.nose_height, s.rise_velocity, s.nose_gas_velocity, s.throughflow_ratio, s.area, attached,
          s.equivalent_diameter, s.bed_height, s.erupted ? 1.0 : 0.0, id, s.nose_x};
}

std::string bubble_csv_row(const BubbleSample& s) {
  const std::string attached = s.attached ? (*s.attached ? "1" : "0") : "";
  const std::string id = s.bubble_id >= 0 ? fmt::format("{}", s.bubble_id) : std::string();
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", s.time, opt(s.nose_height), opt(s.rise_velocity),
                     opt(s.nose_gas_velocity), opt(s.throughflow_ratio), opt(s.area), attached,
                     opt(s.equivalent_diameter), opt(s.bed_height), s.erupted ? 1 : 0, id, opt(s.nose_x));
}

}  // namespace fluidbed
