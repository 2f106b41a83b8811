#include "analysis/bubble_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "analysis/bed_surface.hpp"
#include "analysis/rise_velocity.hpp"
#include "core/error.hpp"

namespace fluidbed {

double threshold_crossing(double y_lo, double eps_lo, double y_hi, double eps_hi, double threshold) {
  const double d = eps_lo - eps_hi;
  if (d == 0.0) return y_hi;
  const double s = std::clamp((eps_lo - threshold) / d, 0.0, 1.0);
  return y_lo + s * (y_hi - y_lo);
}

template <int Dim>
double interpolate_cell_centred(const CellView<Dim>& f, const std::array<double, Dim>& x) {
  const CellGeometry<Dim>& g = f.geometry;
  // Position in units of cells measured from the first cell centre; clamped so the stencil stays on the grid.
  std::array<int, Dim> lo{}, hi{};
  std::array<double, Dim> w{};
  for (int a = 0; a < Dim; ++a) {
    const double s = std::clamp((x[a] - g.origin[a]) / g.h[a] - 0.5, 0.0, static_cast<double>(g.n[a] - 1));
    lo[a] = std::min(static_cast<int>(s), g.n[a] - 1);
    hi[a] = std::min(lo[a] + 1, g.n[a] - 1);
    w[a] = s - lo[a];
  }
  const auto value = [&](int i, int j, int k) {
    Index<Dim> c{};
    c[0] = i;
    c[1] = j;
    if constexpr (Dim == 3) c[2] = k;
    return f[c];
  };
  const auto bilinear = [&](int k) {
    const double wx = w[0], wy = w[1];
    const int i0 = lo[0], i1 = hi[0], j0 = lo[1], j1 = hi[1];
    return (1.0 - wy) * ((1.0 - wx) * value(i0, j0, k) + wx * value(i1, j0, k)) +
           wy * ((1.0 - wx) * value(i0, j1, k) + wx * value(i1, j1, k));
  };
  if constexpr (Dim == 2) {
    return bilinear(0);
  } else {
    return (1.0 - w[2]) * bilinear(lo[2]) + w[2] * bilinear(hi[2]);
  }
}

template <int Dim>
int label_regions(const Index<Dim>& n, const std::vector<std::uint8_t>& mask, std::vector<int>& label) {
  const CellGeometry<Dim> g{n, {}, {}};
  const std::size_t cells = g.cells();
  if (mask.size() != cells)
    throw_input_error(fmt::format("label regions: mask of {} cells for a grid of {}", mask.size(), cells));
  label.assign(cells, -1);
  std::vector<std::size_t> stack;
  int count = 0;
  for (std::size_t start = 0; start < cells; ++start) {
    if (!mask[start] || label[start] >= 0) continue;
    label[start] = count;
    stack.push_back(start);
    while (!stack.empty()) {
      const Index<Dim> c = g.cell_of(stack.back());
      stack.pop_back();
      // Face neighbours only: 4 in 2D, 6 in 3D; cells touching along an edge or a corner are not connected.
      for (int a = 0; a < Dim; ++a) {
        for (const int step : {-1, 1}) {
          Index<Dim> d = c;
          d[a] += step;
          if (d[a] < 0 || d[a] >= n[a]) continue;
          const std::size_t kk = g.index(d);
          if (mask[kk] && label[kk] < 0) {
            label[kk] = count;
            stack.push_back(kk);
          }
        }
      }
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
  if (!(config_.jet_depth >= 0.0)) throw_input_error("bubble jet depth must not be negative");
  if (!(config_.gravity >= 0.0)) throw_input_error("bubble gravity must not be negative");
  if (config_.rise_velocity_samples < 2) throw_input_error("bubble rise_velocity_samples must be at least 2");
}

namespace {

template <int Dim>
struct RegionStats {
  std::size_t cells = 0;
  bool freeboard = false;
  bool attached = false;
  std::array<double, Dim> sum{};  // of the cell centres, for the centroid
  Index<Dim> top = [] {
    Index<Dim> c{};
    c.fill(-1);
    return c;
  }();
};

// Length of the overlap of [a, b] and [lo, hi] exceeds a sliver of the cell size h.
bool overlaps(double a, double b, double lo, double hi, double h) { return std::min(b, hi) - std::max(a, lo) > 1e-9 * h; }

// The horizontal axes of a bed: x, and z in 3D (y is up).
template <int Dim>
constexpr std::array<int, Dim - 1> horizontal_axes() {
  if constexpr (Dim == 2) {
    return {0};
  } else {
    return {0, 2};
  }
}

}  // namespace

namespace {

// The nose line and the jet centre: (jet_x) in 2D, (jet_x, jet_z) in 3D.
template <int Dim>
std::array<double, Dim> jet_line(const BubbleConfig& config, const CellGeometry<Dim>& g) {
  std::array<double, Dim> line{};
  line[0] = config.jet_x;
  if constexpr (Dim == 3) line[2] = config.jet_z.value_or(g.origin[2] + 0.5 * g.length(2));
  return line;
}

template <int Dim>
double horizontal_distance(const CellGeometry<Dim>& g, const std::array<double, Dim>& line, const Index<Dim>& c) {
  if constexpr (Dim == 2) {
    return std::abs(g.centre(0, c[0]) - line[0]);
  } else {
    return std::hypot(g.centre(0, c[0]) - line[0], g.centre(2, c[2]) - line[2]);
  }
}

// Bottom cells "above the jet": every cell of the bottom layer whose face overlaps the jet's footprint, at least
// the one holding the jet centre. Stored per (i, k), i fastest.
template <int Dim>
std::vector<std::uint8_t> jet_cells(const BubbleConfig& config, const CellGeometry<Dim>& g,
                                    const std::array<double, Dim>& line) {
  const int nx = g.n[0];
  const int nz = Dim == 3 ? g.n[Dim - 1] : 1;
  const double jet_lo = config.jet_x - 0.5 * config.jet_width;
  const double jet_hi = config.jet_x + 0.5 * config.jet_width;
  std::vector<std::uint8_t> jet_cell(static_cast<std::size_t>(nx) * static_cast<std::size_t>(nz), 0);
  for (int k = 0; k < nz; ++k) {
    for (int i = 0; i < nx; ++i) {
      const double a = g.origin[0] + i * g.h[0];
      const double b = a + g.h[0];
      bool over = false;
      if (Dim == 2 || config.jet_shape == InletShape::Slot) {
        over = overlaps(a, b, jet_lo, jet_hi, g.h[0]);
      } else if (config.jet_shape == InletShape::Rectangle) {
        const double c = g.face(Dim - 1, k), d = c + g.h[Dim - 1];
        over = overlaps(a, b, jet_lo, jet_hi, g.h[0]) &&
               overlaps(c, d, line[Dim - 1] - 0.5 * config.jet_depth, line[Dim - 1] + 0.5 * config.jet_depth,
                        g.h[Dim - 1]);
      } else {
        // Disc: the face's point nearest the centre lies inside the disc (by more than a sliver).
        const double c = g.face(Dim - 1, k), d = c + g.h[Dim - 1];
        const double px = std::clamp(line[0], a, b), pz = std::clamp(line[Dim - 1], c, d);
        over = std::hypot(px - line[0], pz - line[Dim - 1]) < 0.5 * config.jet_width - 1e-9 * g.h[0];
      }
      if (over) jet_cell[static_cast<std::size_t>(k) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i)] = 1;
    }
  }
  const int ic = g.cell(0, line[0]);
  const int kc = Dim == 3 ? g.cell(Dim - 1, line[Dim - 1]) : 0;
  jet_cell[static_cast<std::size_t>(kc) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(ic)] = 1;
  return jet_cell;
}

// Each void region's cell count, centroid sum, whether it reaches the freeboard (above row j_surf) or sits on the
// jet, and its highest cell (the one nearest the nose line among equals).
template <int Dim>
std::vector<RegionStats<Dim>> region_stats(const CellGeometry<Dim>& g, const std::vector<int>& label, int n_regions,
                                           int j_surf, const std::vector<std::uint8_t>& jet_cell,
                                           const std::array<double, Dim>& line) {
  const int nx = g.n[0];
  std::vector<RegionStats<Dim>> region(static_cast<std::size_t>(n_regions));
  for (std::size_t cell = 0; cell < g.cells(); ++cell) {
    const int l = label[cell];
    if (l < 0) continue;
    const Index<Dim> c = g.cell_of(cell);
    const int j = c[1];
    const int kz = Dim == 3 ? c[Dim - 1] : 0;
    RegionStats<Dim>& r = region[static_cast<std::size_t>(l)];
    ++r.cells;
    for (int a = 0; a < Dim; ++a) r.sum[a] += g.centre(a, c[a]);
    if (j_surf < 0 || j > j_surf) r.freeboard = true;
    if (j == 0 && jet_cell[static_cast<std::size_t>(kz) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(c[0])])
      r.attached = true;
    const bool closer = r.top[1] == j && horizontal_distance<Dim>(g, line, c) < horizontal_distance<Dim>(g, line, r.top);
    if (j > r.top[1] || closer) r.top = c;
  }
  return region;
}

// The tracked bubble's successor: the candidate region sharing most cells with it, and the cells it shares with the
// freeboard (an eruption when they are more).
struct Successor {
  int chosen = -1;
  std::size_t best = 0, free_overlap = 0;
};
template <int Dim, class IsCandidate>
Successor successor(const std::vector<std::uint8_t>& tracked, const std::vector<int>& label,
                    const std::vector<RegionStats<Dim>>& region, IsCandidate is_candidate) {
  std::vector<std::size_t> overlap(region.size(), 0);
  if (tracked.size() == label.size()) {
    for (std::size_t k = 0; k < label.size(); ++k)
      if (tracked[k] && label[k] >= 0) ++overlap[static_cast<std::size_t>(label[k])];
  }
  Successor out;
  for (int l = 0; l < static_cast<int>(region.size()); ++l) {
    const std::size_t o = overlap[static_cast<std::size_t>(l)];
    if (region[static_cast<std::size_t>(l)].freeboard) {
      out.free_overlap += o;
    } else if (is_candidate(l) && o > out.best) {
      out.best = o;
      out.chosen = l;
    }
  }
  if (out.chosen >= 0 && out.free_overlap > out.best) out.chosen = -1;
  return out;
}

// A new bubble: the one on the jet if there is one, else the largest void in the bed; -1 when there is none.
template <int Dim, class IsCandidate>
int new_bubble(const std::vector<RegionStats<Dim>>& region, IsCandidate is_candidate) {
  std::size_t best = 0;
  bool best_attached = false;
  int chosen = -1;
  for (int l = 0; l < static_cast<int>(region.size()); ++l) {
    if (!is_candidate(l)) continue;
    const RegionStats<Dim>& r = region[static_cast<std::size_t>(l)];
    if ((r.attached && !best_attached) || (r.attached == best_attached && r.cells > best)) {
      best = r.cells;
      best_attached = r.attached;
      chosen = l;
    }
  }
  return chosen;
}

// Nose: top of the bubble (region `chosen`) on the vertical line through the jet centre, eps interpolated (linearly
// in 2D, bilinearly over x and z in 3D) between the nearest columns of cell centres; if the bubble has drifted off
// that line, on the column of its highest cell `top`. Returns the height and the column's horizontal position.
template <int Dim>
std::pair<double, std::array<double, Dim>> nose_of(const CellView<Dim>& eps, const std::vector<int>& label, int chosen,
                                                   const std::array<double, Dim>& line, const Index<Dim>& top,
                                                   double thr) {
  const CellGeometry<Dim>& g = eps.geometry;
  const int ny = g.n[1];
  std::array<int, Dim> c0{}, c1{};
  std::array<double, Dim> wl{};
  for (const int a : horizontal_axes<Dim>()) {
    const double sa = (line[a] - g.origin[a]) / g.h[a] - 0.5;
    c0[a] = static_cast<int>(std::floor(sa));
    wl[a] = sa - c0[a];
    if (c0[a] < 0) {
      c0[a] = 0;
      wl[a] = 0.0;
    } else if (c0[a] >= g.n[a] - 1) {
      c0[a] = g.n[a] - 1;
      wl[a] = 0.0;
    }
    c1[a] = std::min(c0[a] + 1, g.n[a] - 1);
  }
  const auto at = [&](int i, int j, int k) {
    Index<Dim> c{};
    c[0] = i;
    c[1] = j;
    if constexpr (Dim == 3) c[2] = k;
    return g.index(c);
  };
  const auto line_eps = [&](int j) {
    const double wx = wl[0];
    const auto row = [&](int k) { return (1.0 - wx) * eps.at(at(c0[0], j, k)) + wx * eps.at(at(c1[0], j, k)); };
    if constexpr (Dim == 2) {
      return row(0);
    } else {
      return (1.0 - wl[2]) * row(c0[2]) + wl[2] * row(c1[2]);
    }
  };
  const auto line_in_bubble = [&](int j) {
    // Every column of the stencil with a nonzero weight counts.
    const auto in = [&](int i, int k) { return label[at(i, j, k)] == chosen; };
    const bool row0 = in(c0[0], Dim == 3 ? c0[Dim - 1] : 0) || (wl[0] > 0.0 && in(c1[0], Dim == 3 ? c0[Dim - 1] : 0));
    if constexpr (Dim == 2) {
      return row0;
    } else {
      return row0 || (wl[2] > 0.0 && (in(c0[0], c1[2]) || (wl[0] > 0.0 && in(c1[0], c1[2]))));
    }
  };
  int j_top = -1;
  for (int j = ny - 1; j >= 0 && j_top < 0; --j) {
    if (line_in_bubble(j) && line_eps(j) > thr) j_top = j;
  }
  std::array<double, Dim> where = line;
  if (j_top >= 0) {
    const double nose = (j_top + 1 < ny && line_eps(j_top + 1) <= thr)
                            ? threshold_crossing(g.centre(1, j_top), line_eps(j_top), g.centre(1, j_top + 1),
                                                 line_eps(j_top + 1), thr)
                            : g.origin[1] + (j_top + 1) * g.h[1];
    return {nose, where};
  }
  where[0] = g.centre(0, top[0]);
  if constexpr (Dim == 3) where[2] = g.centre(2, top[2]);
  const int jt = top[1];
  Index<Dim> above = top;
  above[1] = jt + 1;
  const double nose = (jt + 1 < ny) ? threshold_crossing(g.centre(1, jt), eps[top], g.centre(1, jt + 1), eps[above], thr)
                                    : g.origin[1] + (jt + 1) * g.h[1];
  return {nose, where};
}

}  // namespace

void BubbleTracker::update_rise(double t, double nose, BubbleSample& s) {
  // Least-squares slope of the nose height over the last rise_velocity_samples samples.
  nose_t_.push_back(t);
  nose_h_.push_back(nose);
  const std::size_t keep = static_cast<std::size_t>(config_.rise_velocity_samples);
  if (nose_t_.size() > keep) {
    nose_t_.erase(nose_t_.begin());
    nose_h_.erase(nose_h_.begin());
  }
  if (nose_t_.size() >= 2) s.rise_velocity = rise_slope(nose_t_, nose_h_);
  // The centroid over the same samples (fewer after a restore from a checkpoint that did not hold them).
  centroid_h_.push_back(*s.centroid_y);
  if (centroid_h_.size() > nose_t_.size())
    centroid_h_.erase(centroid_h_.begin(), centroid_h_.end() - static_cast<std::ptrdiff_t>(nose_t_.size()));
  if (centroid_h_.size() >= 2) {
    const std::vector<double> tc(nose_t_.end() - static_cast<std::ptrdiff_t>(centroid_h_.size()), nose_t_.end());
    s.centroid_rise_velocity = rise_slope(tc, centroid_h_);
  }
}

template <int Dim>
BubbleSample BubbleTracker::observe(double t, const CellView<Dim>& eps, const CellView<Dim>& vg) {
  static_assert(Dim == 2 || Dim == 3);
  const CellGeometry<Dim>& g = eps.geometry;
  if (vg.geometry.n != g.n) throw_input_error("bubble tracker: the gas velocity and voidage grids differ");
  const Index<3>& want = config_.cells;
  if ((want[0] > 0 && want[0] != g.n[0]) || (want[1] > 0 && want[1] != g.n[1]))
    throw_input_error(fmt::format("bubble tracker: configured for a {}x{} grid, given {}x{}", want[0], want[1], g.n[0],
                                  g.n[1]));
  if constexpr (Dim == 3) {
    if (want[2] > 0 && want[2] != g.n[2])
      throw_input_error(fmt::format("bubble tracker: configured for {} cells in depth, given {}", want[2], g.n[2]));
  }
  const double thr = config_.eps_threshold;
  const std::array<double, Dim> line = jet_line<Dim>(config_, g);
  BubbleSample s;
  s.time = t;
  s.dimension = Dim;

  // Bed surface: highest layer whose mean voidage is still that of a bed; layers above it are freeboard.
  const int j_surf = bed_surface_row(eps, config_.surface_eps);
  if (j_surf >= 0) s.bed_height = g.origin[1] + (j_surf + 1) * g.h[1];

  const std::size_t n_cells = g.cells();
  std::vector<std::uint8_t> mask(n_cells);
  for (std::size_t k = 0; k < n_cells; ++k) mask[k] = eps.at(k) > thr ? 1 : 0;
  std::vector<int> label;
  const int n_regions = label_regions<Dim>(g.n, mask, label);
  const std::vector<RegionStats<Dim>> region =
      region_stats<Dim>(g, label, n_regions, j_surf, jet_cells<Dim>(config_, g, line), line);
  const double cell_measure = g.cell_measure();
  const double min_measure = Dim == 2 ? config_.min_area : config_.min_volume;
  const auto is_candidate = [&](int l) {
    const RegionStats<Dim>& r = region[static_cast<std::size_t>(l)];
    return !r.freeboard && static_cast<double>(r.cells) * cell_measure >= min_measure;
  };

  int chosen = -1;
  if (tracking_) {
    // The tracked bubble is the region sharing most cells with it at the previous sample.
    const Successor next = successor<Dim>(tracked_, label, region, is_candidate);
    chosen = next.chosen;
    if (chosen < 0) {
      tracking_ = false;
      if (next.free_overlap > 0) {
        s.erupted = true;
        if (!eruption_time_) eruption_time_ = t;
      }
    }
  }
  if (!tracking_ && !s.erupted) {
    chosen = new_bubble<Dim>(region, is_candidate);
    if (chosen >= 0) {
      tracking_ = true;
      was_attached_ = false;
      nose_t_.clear();
      nose_h_.clear();
      centroid_h_.clear();
      ++bubble_count_;
    }
  }
  if (chosen < 0) {
    tracked_.clear();
    return s;
  }

  const RegionStats<Dim>& r = region[static_cast<std::size_t>(chosen)];
  s.bubble_id = bubble_count_ - 1;
  const double measure = static_cast<double>(r.cells) * cell_measure;
  if constexpr (Dim == 2) {
    s.area = measure;
    s.equivalent_diameter = std::sqrt(4.0 * measure / std::numbers::pi);
  } else {
    // Sphere of the same volume: V = pi d^3 / 6.
    s.volume = measure;
    s.equivalent_diameter = std::cbrt(6.0 * measure / std::numbers::pi);
  }
  s.theory_rise_velocity = rise_constant<Dim>() * std::sqrt(config_.gravity * *s.equivalent_diameter);
  s.centroid_x = r.sum[0] / static_cast<double>(r.cells);
  s.centroid_y = r.sum[1] / static_cast<double>(r.cells);
  if constexpr (Dim == 3) s.centroid_z = r.sum[2] / static_cast<double>(r.cells);
  s.attached = r.attached;
  if (was_attached_ && !r.attached) {
    s.detached = true;
    if (!detachment_time_) detachment_time_ = t;
  }
  was_attached_ = r.attached;

  const auto [nose, where] = nose_of<Dim>(eps, label, chosen, line, r.top, thr);
  s.nose_x = where[0];
  if constexpr (Dim == 3) s.nose_z = where[2];
  s.nose_height = nose;
  update_rise(t, nose, s);

  // Axial interstitial gas velocity in the emulsion just above the roof: half a cell above the nose.
  std::array<double, Dim> probe{};
  probe[0] = *s.nose_x;
  probe[1] = nose + 0.5 * g.h[1];
  if constexpr (Dim == 3) probe[2] = *s.nose_z;
  s.nose_gas_velocity = interpolate_cell_centred<Dim>(vg, probe);
  // Throughflow relative to the rising nose, in units of U_mf (Table 2).
  if (s.rise_velocity) s.throughflow_ratio = (*s.nose_gas_velocity - *s.rise_velocity) / config_.u_mf;

  tracked_.assign(label.size(), 0);
  for (std::size_t k = 0; k < label.size(); ++k) tracked_[k] = label[k] == chosen ? 1 : 0;
  return s;
}

template BubbleSample BubbleTracker::observe<2>(double, const CellView<2>&, const CellView<2>&);
template BubbleSample BubbleTracker::observe<3>(double, const CellView<3>&, const CellView<3>&);
template double interpolate_cell_centred<2>(const CellView<2>&, const std::array<double, 2>&);
template double interpolate_cell_centred<3>(const CellView<3>&, const std::array<double, 3>&);
template int label_regions<2>(const Index<2>&, const std::vector<std::uint8_t>&, std::vector<int>&);
template int label_regions<3>(const Index<3>&, const std::vector<std::uint8_t>&, std::vector<int>&);

}  // namespace fluidbed
