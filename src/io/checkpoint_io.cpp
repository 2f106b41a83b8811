#include "io/checkpoint_io.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/error.hpp"

namespace fluidbed {

namespace {

std::string join(const std::string& group, const std::string& name) { return group.empty() ? name : group + "/" + name; }

void ensure_group(Hdf5File& file, const std::string& group) {
  if (!group.empty() && !file.has(group)) file.create_group(group);
}

template <class T>
void check_count(const Hdf5File& file, const std::string& path, const std::vector<T>& v, std::size_t count) {
  if (v.size() != count) {
    throw_input_error(fmt::format("{}: {} has {} values, {} expected", file.path().string(), path, v.size(), count));
  }
}

}  // namespace

void write_components(Hdf5File& file, const std::string& group, const std::vector<NamedComponent>& components) {
  ensure_group(file, group);
  for (const NamedComponent& c : components) {
    file.write(join(group, c.name), c.values);
  }
}

std::vector<std::vector<double>> read_components(const Hdf5File& file, const std::string& group,
                                                 const std::vector<std::string>& names, std::size_t count) {
  std::vector<std::vector<double>> out;
  out.reserve(names.size());
  for (const std::string& n : names) {
    out.push_back(file.read_double(join(group, n)));
    check_count(file, join(group, n), out.back(), count);
  }
  return out;
}

template <int Dim>
void write_field(Hdf5File& file, const std::string& name, const Field<Dim>& field) {
  const auto slash = name.rfind('/');
  if (slash != std::string::npos) ensure_group(file, name.substr(0, slash));
  file.write(name, field.data());
  file.set_attribute(name, "dimension", Dim);
  file.set_attribute(name, "ghost", field.ghost());
  for (int a = 0; a < Dim; ++a) {
    file.set_attribute(name, fmt::format("lo{}", a), field.box().lo[a]);
    file.set_attribute(name, fmt::format("hi{}", a), field.box().hi[a]);
  }
}

template <int Dim>
void read_field(const Hdf5File& file, const std::string& name, Field<Dim>& field) {
  auto shape = [](int dim, int ghost, const std::vector<std::pair<int, int>>& box) {
    std::string s = fmt::format("{}D, ghost {}, cells", dim, ghost);
    for (const auto& [lo, hi] : box) s += fmt::format(" [{}, {})", lo, hi);
    return s;
  };
  std::vector<std::pair<int, int>> want;
  for (int a = 0; a < Dim; ++a) want.emplace_back(field.box().lo[a], field.box().hi[a]);
  const int dim = static_cast<int>(file.attribute_int64(name, "dimension"));
  const int ghost = static_cast<int>(file.attribute_int64(name, "ghost"));
  std::vector<std::pair<int, int>> got;
  for (int a = 0; a < dim && a < 3; ++a) {
    got.emplace_back(static_cast<int>(file.attribute_int64(name, fmt::format("lo{}", a))),
                     static_cast<int>(file.attribute_int64(name, fmt::format("hi{}", a))));
  }
  if (dim != Dim || ghost != field.ghost() || got != want) {
    throw_input_error(fmt::format("{}: {} is {}; the case needs {}", file.path().string(), name,
                                  shape(dim, ghost, got), shape(Dim, field.ghost(), want)));
  }
  std::vector<double> v = file.read_double(name);
  check_count(file, name, v, field.data().size());
  field.data() = std::move(v);
}

template void write_field<2>(Hdf5File&, const std::string&, const Field<2>&);
template void write_field<3>(Hdf5File&, const std::string&, const Field<3>&);
template void read_field<2>(const Hdf5File&, const std::string&, Field<2>&);
template void read_field<3>(const Hdf5File&, const std::string&, Field<3>&);

namespace {

// The spin datasets: about z alone in 2D (today's name), three components in 3D.
std::vector<std::pair<std::size_t, std::string>> spin_names(int dimension) {
  if (dimension == 3) return {{0, "omega_x"}, {1, "omega_y"}, {2, "omega_z"}};
  return {{2, "omega"}};
}

}  // namespace

void write_particle_arrays(Hdf5File& file, const std::string& group, const ParticleArrays& p) {
  ensure_group(file, group);
  const int axes = p.dimension == 3 ? 3 : 2;
  file.write(join(group, "id"), p.id);
  file.write(join(group, "species"), p.species);
  if (p.layer.empty()) {
    file.write(join(group, "layer"), p.size(),
               [](std::size_t, std::size_t n, std::int32_t* dst) { std::fill_n(dst, n, std::int32_t{0}); });
  } else {
    file.write(join(group, "layer"), p.layer);
  }
  std::vector<NamedComponent> c;
  const auto xn = axis_names<3>(""), vn = axis_names<3>("v");
  for (int a = 0; a < axes; ++a) c.push_back({xn[static_cast<std::size_t>(a)], p.x[static_cast<std::size_t>(a)]});
  for (int a = 0; a < axes; ++a) c.push_back({vn[static_cast<std::size_t>(a)], p.v[static_cast<std::size_t>(a)]});
  for (const auto& [a, n] : spin_names(p.dimension)) c.push_back({n, p.omega[a]});
  write_components(file, group, c);
}

ParticleArraysData read_particle_arrays(const Hdf5File& file, const std::string& group, int dimension) {
  ParticleArraysData d;
  d.dimension = dimension;
  const int axes = dimension == 3 ? 3 : 2;
  d.id = file.read_int64(join(group, "id"));
  const std::size_t n = d.id.size();
  d.species = file.read_int32(join(group, "species"));
  check_count(file, join(group, "species"), d.species, n);
  d.layer = file.read_int32(join(group, "layer"));
  check_count(file, join(group, "layer"), d.layer, n);
  const auto xn = axis_names<3>(""), vn = axis_names<3>("v");
  for (int a = 0; a < axes; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    d.x[ua] = std::move(read_components(file, group, {xn[ua]}, n)[0]);
    d.v[ua] = std::move(read_components(file, group, {vn[ua]}, n)[0]);
  }
  for (const auto& [a, name] : spin_names(dimension)) d.omega[a] = std::move(read_components(file, group, {name}, n)[0]);
  return d;
}

ParticleArrays ParticleArraysData::view() const {
  ParticleArrays a;
  a.dimension = dimension;
  a.id = id;
  a.species = species;
  a.layer = layer;
  for (std::size_t k = 0; k < 3; ++k) {
    a.x[k] = x[k];
    a.v[k] = v[k];
    a.omega[k] = omega[k];
  }
  return a;
}

}  // namespace fluidbed
