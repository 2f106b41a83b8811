#include "analysis/bubble_population.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "analysis/bed_surface.hpp"
#include "analysis/bubble_tracker.hpp"
#include "analysis/rise_velocity.hpp"
#include "core/error.hpp"

namespace fluidbed {

const char* bubble_event_name(BubbleEvent e) {
  switch (e) {
    case BubbleEvent::None:
      return "";
    case BubbleEvent::Birth:
      return "birth";
    case BubbleEvent::Split:
      return "split";
    case BubbleEvent::Coalescence:
      return "coalescence";
    case BubbleEvent::Eruption:
      return "eruption";
    case BubbleEvent::Disappearance:
      return "disappearance";
  }
  return "";
}

namespace {

template <int Dim>
struct Region {
  std::size_t cells = 0;
  bool excluded_free = false;         // has a cell above the bed surface
  bool excluded_distributor = false;  // has a cell centre in the distributor zone
  std::array<double, Dim> sum{};
  std::array<double, Dim> lo, hi;  // threshold contour extents per axis
  Region() {
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
  }
};

// Regions that span the bed's cross-section: a cell in every column along each horizontal axis (x; x and z in 3D).
// Such a void parts the bed above it from the bed below (a slug, or a plug lifted off the distributor), so it is no
// bubble rising through the bed. Without wrap-around in the labels, a connected region has every column exactly when
// it touches both side walls, and along a periodic axis the whole axis is the test either way.
template <int Dim>
std::vector<std::uint8_t> spanning_regions(const CellGeometry<Dim>& g, const std::vector<int>& label, int n_regions) {
  std::vector<std::uint8_t> spans(static_cast<std::size_t>(n_regions), 1);
  for (int a = 0; a < Dim; a += 2) {  // the horizontal axes: 0, and 2 in 3D (axis 1 is up)
    const std::size_t n = static_cast<std::size_t>(g.n[a]);
    std::vector<std::uint8_t> column(spans.size() * n, 0);  // [region][column along a]
    for (std::size_t k = 0; k < label.size(); ++k) {
      if (label[k] < 0) continue;
      column[static_cast<std::size_t>(label[k]) * n + static_cast<std::size_t>(g.cell_of(k)[a])] = 1;
    }
    for (std::size_t l = 0; l < spans.size(); ++l) {
      spans[l] = spans[l] && std::all_of(column.begin() + static_cast<std::ptrdiff_t>(l * n),
                                         column.begin() + static_cast<std::ptrdiff_t>((l + 1) * n),
                                         [](std::uint8_t c) { return c != 0; });
    }
  }
  return spans;
}

// The frame of a sample: the bed between the distributor zone and the surface row j_surf, the bubbles in it; slugs
// are counted apart, neither in the bubble count nor in the bubble measure.
template <int Dim>
BubbleFrame frame_of(double t, const CellGeometry<Dim>& g, int j_surf, double y_dist,
                     const std::vector<BubbleRecord<Dim>>& now) {
  BubbleFrame f;
  f.time = t;
  if (j_surf >= 0) {
    f.bed_height = g.face(1, j_surf + 1);
    double across = g.length(0);
    if constexpr (Dim == 3) across *= g.length(2);
    f.bed_measure = std::max(0.0, *f.bed_height - y_dist) * across;
  }
  for (const BubbleRecord<Dim>& b : now) {
    if (b.slug) {
      ++f.slugs;
    } else {
      f.bubble_measure += b.size;
      ++f.bubbles;
    }
  }
  return f;
}

}  // namespace

template <int Dim>
BubblePopulation<Dim>::BubblePopulation(const PopulationConfig& config) : config_(config) {
  static_assert(Dim == 2 || Dim == 3);
  if (!(config_.eps_threshold > 0.0 && config_.eps_threshold < 1.0))
    throw_input_error(
        fmt::format("bubble population: threshold voidage must lie in (0, 1), got {}", config_.eps_threshold));
  if (!(config_.distributor_height >= 0.0))
    throw_input_error("bubble population: distributor_height must not be negative");
  if (!(config_.min_size >= 0.0)) throw_input_error("bubble population: min_size must not be negative");
  if (config_.velocity_samples < 2) throw_input_error("bubble population: velocity_samples must be at least 2");
}

namespace {

// The regions' cell counts, centroid sums, exclusions (above the bed surface row j_surf, below y_dist) and the
// extents of their eps = threshold contour along each axis: linear between the centres of a boundary cell and its
// neighbour outside (exact for a linear eps profile), the grid's own face where the region touches it.
template <int Dim>
std::vector<Region<Dim>> measure_regions(const CellView<Dim>& eps, const std::vector<int>& label, int n_regions,
                                         double thr, int j_surf, double y_dist) {
  const CellGeometry<Dim>& g = eps.geometry;
  std::vector<Region<Dim>> region(static_cast<std::size_t>(n_regions));
  for (std::size_t k = 0; k < g.cells(); ++k) {
    const int l = label[k];
    if (l < 0) continue;
    Region<Dim>& r = region[static_cast<std::size_t>(l)];
    const Index<Dim> c = g.cell_of(k);
    ++r.cells;
    for (int a = 0; a < Dim; ++a) r.sum[a] += g.centre(a, c[a]);
    if (j_surf < 0 || c[1] > j_surf) r.excluded_free = true;
    if (g.centre(1, c[1]) < y_dist) r.excluded_distributor = true;
    for (int a = 0; a < Dim; ++a) {
      for (const int step : {-1, 1}) {
        Index<Dim> d = c;
        d[a] += step;
        double x;
        if (d[a] < 0 || d[a] >= g.n[a]) {
          x = step > 0 ? g.face(a, c[a] + 1) : g.face(a, c[a]);
        } else if (label[g.index(d)] == l) {
          continue;
        } else {
          x = step > 0 ? threshold_crossing(g.centre(a, c[a]), eps[c], g.centre(a, d[a]), eps[d], thr)
                       : threshold_crossing(g.centre(a, d[a]), eps[d], g.centre(a, c[a]), eps[c], thr);
        }
        r.lo[a] = std::min(r.lo[a], x);
        r.hi[a] = std::max(r.hi[a], x);
      }
    }
  }
  return region;
}

// Association by shared cells: overlap[(previous id, region)], the previous bubbles' overlap with the freeboard,
// and from the overlaps each previous id's bubble regions and each region's previous ids.
struct Links {
  std::map<std::pair<int, int>, std::size_t> overlap;
  std::map<int, std::size_t> free_overlap;
  std::map<int, std::vector<int>> children;  // previous id -> bubble regions
  std::map<int, std::vector<int>> parents;   // region -> previous ids
};
template <int Dim, class IsBubble>
Links link_regions(const std::vector<int>& owner, const std::vector<int>& label, const std::vector<Region<Dim>>& region,
                   IsBubble is_bubble) {
  Links k;
  for (std::size_t c = 0; c < owner.size(); ++c) {
    const int id = owner[c], l = label[c];
    if (id < 0 || l < 0) continue;
    if (is_bubble(l)) {
      ++k.overlap[{id, l}];
    } else if (region[static_cast<std::size_t>(l)].excluded_free) {
      ++k.free_overlap[id];
    }
  }
  for (const auto& [key, n] : k.overlap) {
    k.children[key.first].push_back(key.second);
    k.parents[key.second].push_back(key.first);
  }
  return k;
}

// The shape of a bubble region: size, equivalent diameter, centroid, nose, tail, width and aspect ratio.
template <int Dim>
BubbleRecord<Dim> record_of(double t, const Region<Dim>& r, bool slug, double cell_measure) {
  BubbleRecord<Dim> b;
  b.time = t;
  b.cells = r.cells;
  b.slug = slug;
  b.size = static_cast<double>(r.cells) * cell_measure;
  // Circle of the same area (2D), sphere of the same volume V = pi d^3 / 6 (3D).
  b.equivalent_diameter =
      Dim == 2 ? std::sqrt(4.0 * b.size / std::numbers::pi) : std::cbrt(6.0 * b.size / std::numbers::pi);
  for (int a = 0; a < Dim; ++a) b.centroid[a] = r.sum[a] / static_cast<double>(r.cells);
  b.nose = r.hi[1];
  b.tail = r.lo[1];
  b.width = Dim == 2 ? r.hi[0] - r.lo[0] : 0.5 * ((r.hi[0] - r.lo[0]) + (r.hi[Dim - 1] - r.lo[Dim - 1]));
  b.aspect_ratio = b.width > 0.0 ? (b.nose - b.tail) / b.width : 0.0;
  return b;
}

}  // namespace

template <int Dim>
void BubblePopulation<Dim>::close_previous(double t, const std::map<int, std::vector<int>>& children,
                                           const std::map<int, std::size_t>& free_overlap,
                                           const std::vector<int>& id_of_region) {
  for (const BubbleRecord<Dim>& p : current_) {
    const auto cit = children.find(p.id);
    if (cit == children.end()) {
      const bool erupted = free_overlap.count(p.id) > 0;
      events_.push_back({t, erupted ? BubbleEvent::Eruption : BubbleEvent::Disappearance, p.id, {}, p.centroid[1]});
      history_.erase(p.id);
    } else if (cit->second.size() > 1) {
      std::vector<int> kids;
      for (const int l : cit->second) kids.push_back(id_of_region[static_cast<std::size_t>(l)]);
      std::sort(kids.begin(), kids.end());
      events_.push_back({t, BubbleEvent::Split, p.id, kids, p.centroid[1]});
      history_.erase(p.id);
    } else if (id_of_region[static_cast<std::size_t>(cit->second.front())] != p.id) {
      history_.erase(p.id);  // merged into another id: the Coalescence event names it
    }
  }
}

template <int Dim>
void BubblePopulation<Dim>::update_velocities(double t, std::vector<BubbleRecord<Dim>>& now) {
  // A merger moves the centroid by a jump that is no rise: the samples start again at every event.
  const std::size_t keep = static_cast<std::size_t>(config_.velocity_samples);
  for (BubbleRecord<Dim>& b : now) {
    History& h = history_[b.id];
    if (b.event != BubbleEvent::None) h = History{};
    h.t.push_back(t);
    h.centroid.push_back(b.centroid[1]);
    h.nose.push_back(b.nose);
    if (h.t.size() > keep) {
      h.t.erase(h.t.begin());
      h.centroid.erase(h.centroid.begin());
      h.nose.erase(h.nose.begin());
    }
    if (h.t.size() >= 2) {
      b.u_centroid = rise_slope(h.t, h.centroid);
      b.u_nose = rise_slope(h.t, h.nose);
    }
  }
}

template <int Dim>
const std::vector<BubbleRecord<Dim>>& BubblePopulation<Dim>::observe(double t, const CellView<Dim>& eps) {
  const CellGeometry<Dim>& g = eps.geometry;
  const std::size_t n_cells = g.cells();
  if (!owner_.empty() && owner_.size() != n_cells)
    throw_input_error(fmt::format("bubble population: {} cells, the previous sample had {}", n_cells, owner_.size()));
  const double thr = config_.eps_threshold;
  sample_events_begin_ = events_.size();

  const int j_surf = bed_surface_row(eps, config_.surface_eps);
  std::vector<std::uint8_t> mask(n_cells);
  for (std::size_t k = 0; k < n_cells; ++k) mask[k] = eps.at(k) > thr ? 1 : 0;
  std::vector<int> label;
  const int n_regions = label_regions<Dim>(g.n, mask, label);
  const double y_dist = g.origin[1] + config_.distributor_height;
  const std::vector<Region<Dim>> region = measure_regions<Dim>(eps, label, n_regions, thr, j_surf, y_dist);
  const std::vector<std::uint8_t> spans = spanning_regions<Dim>(g, label, n_regions);
  const double cell_measure = g.cell_measure();
  const auto is_bubble = [&](int l) {
    const Region<Dim>& r = region[static_cast<std::size_t>(l)];
    return !r.excluded_free && !r.excluded_distributor &&
           static_cast<double>(r.cells) * cell_measure >= config_.min_size;
  };
  Links links = link_regions<Dim>(owner_, label, region, is_bubble);
  std::map<int, std::size_t> previous_cells;
  for (const BubbleRecord<Dim>& b : current_) previous_cells[b.id] = b.cells;

  std::vector<BubbleRecord<Dim>> now;
  std::vector<int> id_of_region(static_cast<std::size_t>(n_regions), -1);
  for (int l = 0; l < n_regions; ++l) {
    if (!is_bubble(l)) continue;
    BubbleRecord<Dim> b = record_of<Dim>(t, region[static_cast<std::size_t>(l)], spans[static_cast<std::size_t>(l)] != 0,
                                         cell_measure);
    const auto pit = links.parents.find(l);
    if (pit == links.parents.end()) {
      b.id = next_id_++;
      b.event = BubbleEvent::Birth;
      events_.push_back({t, BubbleEvent::Birth, b.id, {}, b.centroid[1]});
    } else {
      std::vector<int> ps = pit->second;
      std::sort(ps.begin(), ps.end());
      // A parent whose only child this region is passes its id on; among several, the largest one's id survives.
      int heir = -1;
      for (const int p : ps) {
        if (links.children[p].size() != 1) continue;
        if (heir < 0 || previous_cells[p] > previous_cells[heir]) heir = p;
      }
      b.parents = ps;
      if (heir >= 0) {
        b.id = heir;
        if (ps.size() > 1) {
          b.event = BubbleEvent::Coalescence;
          std::vector<int> others;
          for (const int p : ps)
            if (p != heir) others.push_back(p);
          events_.push_back({t, BubbleEvent::Coalescence, heir, others, b.centroid[1]});
        } else {
          b.parents.clear();
        }
      } else {
        b.id = next_id_++;
        b.event = BubbleEvent::Split;
      }
    }
    id_of_region[static_cast<std::size_t>(l)] = b.id;
    now.push_back(std::move(b));
  }
  close_previous(t, links.children, links.free_overlap, id_of_region);
  update_velocities(t, now);

  owner_.assign(n_cells, -1);
  for (std::size_t k = 0; k < n_cells; ++k)
    if (label[k] >= 0) owner_[k] = id_of_region[static_cast<std::size_t>(label[k])];

  frames_.push_back(frame_of<Dim>(t, g, j_surf, y_dist, now));

  current_ = std::move(now);
  return current_;
}

template <int Dim>
typename BubblePopulation<Dim>::State BubblePopulation<Dim>::state() const {
  State s;
  s.owner = owner_;
  s.next_id = next_id_;
  for (const BubbleRecord<Dim>& b : current_) {
    s.ids.push_back(b.id);
    s.cells.push_back(static_cast<double>(b.cells));
    s.centroid_y.push_back(b.centroid[1]);
    const auto it = history_.find(b.id);
    const std::size_t n = it == history_.end() ? 0 : it->second.t.size();
    s.history_count.push_back(static_cast<int>(n));
    for (std::size_t k = 0; k < n; ++k) {
      s.history_t.push_back(it->second.t[k]);
      s.history_centroid.push_back(it->second.centroid[k]);
      s.history_nose.push_back(it->second.nose[k]);
    }
  }
  return s;
}

template <int Dim>
void BubblePopulation<Dim>::restore(const State& s) {
  const std::size_t n = s.ids.size();
  if (s.cells.size() != n || s.centroid_y.size() != n || s.history_count.size() != n ||
      s.history_centroid.size() != s.history_t.size() || s.history_nose.size() != s.history_t.size())
    throw_input_error("bubble population: inconsistent checkpoint state");
  owner_ = s.owner;
  next_id_ = s.next_id;
  current_.clear();
  history_.clear();
  events_.clear();
  frames_.clear();
  sample_events_begin_ = 0;
  std::size_t at = 0;
  for (std::size_t b = 0; b < n; ++b) {
    BubbleRecord<Dim> r;
    r.id = s.ids[b];
    r.cells = static_cast<std::size_t>(s.cells[b]);
    r.centroid[1] = s.centroid_y[b];
    current_.push_back(r);
    const std::size_t c = static_cast<std::size_t>(s.history_count[b]);
    if (at + c > s.history_t.size()) throw_input_error("bubble population: inconsistent checkpoint state");
    History& h = history_[r.id];
    h.t.assign(s.history_t.begin() + static_cast<std::ptrdiff_t>(at),
               s.history_t.begin() + static_cast<std::ptrdiff_t>(at + c));
    h.centroid.assign(s.history_centroid.begin() + static_cast<std::ptrdiff_t>(at),
                      s.history_centroid.begin() + static_cast<std::ptrdiff_t>(at + c));
    h.nose.assign(s.history_nose.begin() + static_cast<std::ptrdiff_t>(at),
                  s.history_nose.begin() + static_cast<std::ptrdiff_t>(at + c));
    at += c;
  }
}

template class BubblePopulation<2>;
template class BubblePopulation<3>;

}  // namespace fluidbed
