// [grid], [gas] and [inlet]: the cells into CaseConfig::grid (CaseGrid, config/case_config.hpp), the gas and its
// inlet regions into CaseConfig::gas (GasConfig, fluid/gas_config.hpp).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "config/case_check.hpp"
#include "config/case_sections.hpp"
#include "config/settle_record.hpp"
#include "core/error.hpp"
#include "fluid/gas_boundary.hpp"

namespace fluidbed {

namespace case_sections {

namespace {

// A region's velocity schedule, keys under prefix p ("inlet." or "inlet.jet[k]."): inlet.schedule picks the kind;
// u0_key is the region's velocity key (a table replaces it). The background's ramp keys are the start-up ramp's.
InletSchedule read_schedule(CaseReader& r, const std::string& p, const std::string& u0_key, double ramp_start_default,
                            bool background) {
  using R = CaseReader;
  InletSchedule s;
  const std::string kind = r.string(p + "schedule", "constant", "superficial velocity in time: constant, ramp "
                                    "(linear), table (linear between (t, U) pairs), sine (U0 + A sin(2 pi f t + phase)) "
                                    "or square (U0 + A over the duty fraction of each period)",
                                    {"constant", "ramp", "table", "sine", "square"});
  const auto refuse = [&](std::initializer_list<const char*> keys, const std::string& why) {
    for (const char* k : keys)
      if (r.has(p + k)) r.fail(p + k, why);
  };
  if (kind == "constant") {
    if (!background) refuse({"ramp_from", "ramp_start", "ramp_time"}, "ramp keys need schedule = \"ramp\"");
  } else if (kind == "ramp") {
    s.kind = ScheduleKind::Ramp;
    if (!background) {
      s.ramp_from = r.number(p + "ramp_from", 0.0, "m/s", "velocity until ramp_start (schedule = \"ramp\")");
      s.ramp_time = r.required_number(p + "ramp_time", "s", "duration of the linear ramp to the region's velocity "
                                      "(schedule = \"ramp\")", R::positive());
    }
    s.ramp_start = r.number(p + "ramp_start", ramp_start_default, "s", "the ramp begins (schedule = \"ramp\")");
    if (!background) r.describe_default(p + "ramp_start", "the jet's start");
  } else {
    refuse({"ramp_start"}, "ramp_start needs schedule = \"ramp\"");
    if (!background) refuse({"ramp_from", "ramp_time"}, "ramp keys need schedule = \"ramp\"");
  }
  if (kind == "table") {
    s.kind = ScheduleKind::Table;
    if (r.has(u0_key)) r.fail(u0_key, "a table schedule gives the velocities itself (table_velocities or table_file)");
    const std::string file = r.string(p + "table_file", "", "CSV of the table (schedule = \"table\"): one header "
                                      "line, then time_s,velocity_m_s rows; relative to the case file");
    if (!file.empty()) {
      if (r.has(p + "table_times") || r.has(p + "table_velocities")) {
        r.fail(p + "table_file", "give the table inline (table_times, table_velocities) or as a file, not both");
      }
      const auto path = case_relative_path(r.file_name(), file);
      std::ifstream in(path);
      if (!in) r.fail(p + "table_file", fmt::format("cannot read {}", path.string()));
      std::string line;
      std::getline(in, line);
      for (int row = 2; std::getline(in, line); ++row) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream ls(line);
        double t = 0.0, u = 0.0;
        char comma = 0;
        if (!(ls >> t >> comma >> u) || comma != ',') {
          r.fail(p + "table_file", fmt::format("{} line {}: expected time_s,velocity_m_s", path.string(), row));
        }
        s.times.push_back(t);
        s.velocities.push_back(u);
      }
    } else {
      s.times = r.numbers(p + "table_times", {}, "s", "times of the table (schedule = \"table\"), increasing");
      s.velocities = r.numbers(p + "table_velocities", {}, "m/s", "velocities at table_times (schedule = \"table\")");
    }
    if (s.times.empty() || s.times.size() != s.velocities.size()) {
      r.fail(file.empty() ? p + "table_velocities" : p + "table_file",
             fmt::format("a table needs as many velocities as times, at least one (got {} and {})", s.times.size(),
                         s.velocities.size()));
    }
    for (std::size_t k = 1; k < s.times.size(); ++k) {
      if (!(s.times[k] > s.times[k - 1])) {
        r.fail(file.empty() ? p + "table_times" : p + "table_file", "the table's times must increase strictly");
      }
    }
  } else {
    refuse({"table_file", "table_times", "table_velocities"}, "table keys need schedule = \"table\"");
  }
  if (kind == "sine" || kind == "square") {
    s.kind = kind == "sine" ? ScheduleKind::Sine : ScheduleKind::Square;
    s.amplitude = r.number(p + "amplitude", 0.0, "m/s", "pulsation amplitude A (schedule = \"sine\" or \"square\")");
    s.frequency = r.required_number(p + "frequency", "Hz", "pulsation frequency f (schedule = \"sine\" or "
                                    "\"square\")", R::positive());
    s.phase = r.number(p + "phase", 0.0, "rad", "pulsation phase (schedule = \"sine\" or \"square\")");
    if (s.kind == ScheduleKind::Square) {
      s.duty = r.number(p + "duty", 0.5, "", "the on fraction of each period (schedule = \"square\")",
                        R::Range{0.0, 1.0, true, true});
    } else {
      refuse({"duty"}, "duty needs schedule = \"square\"");
    }
  } else {
    refuse({"amplitude", "frequency", "phase", "duty"}, "pulsation keys need schedule = \"sine\" or \"square\"");
  }
  return s;
}

}  // namespace

// [grid]: the cells of the gas, the voidage and the two-fluid model.
void read_grid(CaseReader& r, CaseConfig& c, GasKeys& k) {
  using R = CaseReader;
  const bool needs_gas = c.model == Model::Tfm || c.gas_enabled;
  // [grid]: one staggered grid for the gas, the voidage and the two-fluid model.
  const bool three_d = c.domain.dimension == 3;
  // DEM alone without a [grid]: cells near the paper's 0.02 m that divide the domain, so that a box of any size
  // needs no grid it does not use (the cells then serve turning the gas on with --set only).
  const bool grid_given = r.has("grid.cell_width") || r.has("grid.cell_height") || r.has("grid.cell_depth");
  const bool fitted = !needs_gas && !grid_given;
  const auto fit = [](double length, double min_cells) { return length / std::max(min_cells, std::round(length / 0.02)); };
  const double dx = r.number("grid.cell_width", fitted ? fit(c.domain.width, 2.0) : 0.02, "m",
                             "gas cell width (the paper: 0.02 m)", R::positive());
  r.describe_default("grid.cell_width", "0.02; gas off and no [grid]: the nearest that divides the width");
  const double dy = r.number("grid.cell_height", fitted ? fit(c.domain.height, 2.0) : dx, "m", "gas cell height",
                             R::positive());
  double dz = 0.0;
  if (three_d) {
    dz = r.number("grid.cell_depth", fitted ? fit(c.domain.depth, 1.0) : std::min(dx, c.domain.depth), "m",
                  "gas cell depth (z); 3D only; default: grid.cell_width, or the whole depth when that is less",
                  R::positive());
    r.describe_default("grid.cell_depth", "min(cell_width, domain.depth)");
  } else if (r.has("grid.cell_depth")) {
    r.fail("grid.cell_depth", "a 2D case (case.dimension = 2) has one layer of cells; set case.dimension = 3 for "
                              "cells across a depth");
  }
  const double fx = c.domain.width / dx, fy = c.domain.height / dy, fz = three_d ? c.domain.depth / dz : 1.0;
  if (fx * fy * fz > 1e8) {  // 40 fields of 8 bytes per cell (the TFM): 32 GB
    r.fail("grid.cell_width", three_d ? fmt::format("cells of {} x {} x {} m make {:.3g} cells of the {} x {} x {} m "
                                                    "domain; at most 1e8 fit in memory", dx, dy, dz, fx * fy * fz,
                                                    c.domain.width, c.domain.height, c.domain.depth)
                                      : fmt::format("cells of {} x {} m make {:.3g} cells of the {} x {} m domain; at "
                                                    "most 1e8 fit in memory", dx, dy, fx * fy, c.domain.width,
                                                    c.domain.height));
  }
  if (std::abs(fx - std::round(fx)) > 1e-9 * fx) {
    r.fail("grid.cell_width", fmt::format("{} m does not divide the domain width {} m into whole cells", dx, c.domain.width));
  }
  if (std::abs(fy - std::round(fy)) > 1e-9 * fy) {
    r.fail("grid.cell_height", fmt::format("{} m does not divide the domain height {} m into whole cells", dy, c.domain.height));
  }
  if (three_d && std::abs(fz - std::round(fz)) > 1e-9 * fz) {
    r.fail("grid.cell_depth", fmt::format("{} m does not divide the domain depth {} m into whole cells", dz, c.domain.depth));
  }
  c.grid.dimension = c.domain.dimension;
  c.grid.nx = static_cast<int>(std::lround(fx));
  c.grid.ny = static_cast<int>(std::lround(fy));
  c.grid.dx = c.domain.width / c.grid.nx;
  c.grid.dy = c.domain.height / c.grid.ny;
  c.grid.nz = three_d ? static_cast<int>(std::lround(fz)) : 1;
  c.grid.dz = three_d ? c.domain.depth / c.grid.nz : 0.0;
  // The gas solver's rule (GasSolver refuses fewer cells), here so that `check` refuses what `run` would, gas or not.
  // Across the depth one layer is allowed: a slab one cell deep between front and back walls.
  const std::string who = needs_gas ? "the gas needs" : "the grid needs (the gas is off, but --set gas.enabled=true "
                                                         "would use it)";
  if (c.grid.nx < 2) {
    r.fail("grid.cell_width", fmt::format("{} m leaves {} cell across the domain width {} m; {} at least 2",
                                          dx, c.grid.nx, c.domain.width, who));
  }
  if (c.grid.ny < 2) {
    r.fail("grid.cell_height", fmt::format("{} m leaves {} cell over the domain height {} m; {} at least 2",
                                           dy, c.grid.ny, c.domain.height, who));
  }
  k.dx = dx;
  k.dy = dy;
  k.dz = dz;
}

void read_gas_phase(CaseReader& r, CaseConfig& c, const GasKeys& k) {
  using R = CaseReader;
  const double dx = k.dx;
  GasConfig& g = c.gas;
  g.rho_g = r.number("gas.density", 1.205, "kg/m^3", "gas density rho_g", R::positive());
  g.mu_g = r.number("gas.viscosity", 1.8e-5, "Pa s", "gas viscosity mu_g", R::positive());
  check_gas_plausible(r, g, c.notes);
  if (c.model == Model::Dem && c.gas_enabled) {
    for (std::size_t s = 0; s < c.dem.n_species(); ++s) {
      const std::string p = fmt::format("species[{}].", s);
      check_species_plausible(r, p, c.dem.species[s], c.domain, c.grid);
      if (!(c.dem.species[s].density > g.rho_g)) {
        r.fail(p + "density", fmt::format("particles of {} kg/m^3 are not heavier than the gas ({} kg/m^3): they do "
                                          "not form a bed", c.dem.species[s].density, g.rho_g));
      }
    }
  }
  g.gravity = c.domain.gravity;
  const std::string visc = r.string("gas.viscous_stress", "off", "gas viscous stress (off in the paper's Eq. 12): "
                                    "laplacian div(eps mu grad u), or full div(eps mu (grad u + grad u^T))",
                                    {"off", "laplacian", "full"});
  g.viscous = visc == "off" ? ViscousStress::Off : visc == "full" ? ViscousStress::Full : ViscousStress::Laplacian;
  const std::string conv = r.string("gas.convection", "van_leer", "bounded convection scheme of the gas momentum",
                                    {"upwind", "van_leer", "minmod"});
  g.convection = conv == "upwind" ? ConvectionScheme::Upwind
                 : conv == "minmod" ? ConvectionScheme::Minmod : ConvectionScheme::VanLeer;
  const std::string pc = r.string("gas.pressure_coupling", "simplec", "pressure-velocity coupling", {"simple", "simplec"});
  g.coupling = pc == "simple" ? PressureCoupling::Simple : PressureCoupling::Simplec;
  const std::string ps = r.string("gas.pressure_solver", "eigen", "pressure-correction solver: eigen (direct: band "
                                  "LDLT on 2D grids and thin slabs, else sparse Cholesky), "
                                  "eigen-cg (incomplete-Cholesky CG), hypre-pfmg (structured multigrid CG; needs a build "
                                  "with hypre) or cg-multigrid (multigrid CG with exact inner products: the same bits on "
                                  "any rank count)", {"eigen", "eigen-cg", "hypre-pfmg", "cg-multigrid"});
  g.pressure_solver = ps == "hypre-pfmg"     ? PressureBackend::HyprePfmg
                      : ps == "eigen-cg"     ? PressureBackend::EigenCg
                      : ps == "cg-multigrid" ? PressureBackend::CgMultigrid
                                             : PressureBackend::Eigen;
  // The periodic gas and the periodic two-fluid model (GasSolver's and TfmSolver's rules, here so that `check`
  // refuses what `run` would).
  if (((c.model == Model::Dem && c.gas_enabled) || c.model == Model::Tfm) && c.domain.any_periodic()) {
    if (g.pressure_solver == PressureBackend::HyprePfmg) {
      r.fail("gas.pressure_solver", "hypre-pfmg does not take periodic axes (domain.periodic) in this version: use "
                                    "eigen, eigen-cg or cg-multigrid");
    }
    if (c.domain.periodic[0] && c.grid.nx < 3) {
      r.fail("grid.cell_width", fmt::format("{} m leaves {} cells across the periodic width {} m; a periodic axis "
                                            "needs at least 3", dx, c.grid.nx, c.domain.width));
    }
    if (c.domain.periodic[2] && c.grid.nz < 3) {
      r.fail("grid.cell_depth", fmt::format("{} cells across the periodic depth {} m; a periodic axis needs at "
                                            "least 3", c.grid.nz, c.domain.depth));
    }
  }
  g.relax_velocity = r.number("gas.relax_velocity", 0.8, "", "momentum under-relaxation", R::Range{0.0, 1.0, true, false});
  g.relax_pressure = r.number("gas.relax_pressure", 1.0, "", "pressure under-relaxation", R::Range{0.0, 1.0, true, false});
  g.max_simple_iterations = static_cast<int>(r.integer("gas.max_iterations", 200, "SIMPLE iterations per gas step at most",
                                                       R::between(1, 100000)));
  g.mass_tolerance = r.number("gas.mass_tolerance", 1e-8, "", "SIMPLE stops when the normalised mass residual is below this",
                              R::positive());
  g.momentum_tolerance = r.number("gas.momentum_tolerance", 1e-8, "", "SIMPLE also needs the normalised momentum "
                                  "residual below this", R::positive());
  g.coupling_tolerance = r.number("gas.coupling_tolerance", 0.01, "", "SIMPLE also ends when an iteration moves the "
                                  "mass flux by less than this fraction of the step's change, the particles' one-step "
                                  "lag (0: the fixed tolerances only)", R::Range{0.0, 1.0, false, true});
  g.momentum_solver_tolerance = r.number("gas.momentum_solver_tolerance", 1e-4, "", "each momentum solve reduces "
                                         "its residual by this factor", R::Range{0.0, 1.0, true, true});
  g.pressure_solver_tolerance = r.number("gas.pressure_solver_tolerance", 1e-3, "", "relative residual of the "
                                         "pressure-correction solves after a step's first", R::Range{0.0, 1.0, true, true});
  const std::string side = r.string("gas.side_walls", "no_slip", "tangential gas condition on the side walls", {"slip", "no_slip"});
  g.boundary.side_walls = side == "slip" ? WallKind::Slip : WallKind::NoSlip;
  if (c.domain.dimension == 3) {
    const std::string fb = r.string("gas.front_back_walls", side, "tangential gas condition on the front and back "
                                    "walls of a 3D bed (default: that of gas.side_walls)", {"slip", "no_slip"});
    g.boundary.front_back_walls = fb == "slip" ? WallKind::Slip : WallKind::NoSlip;
  } else if (r.has("gas.front_back_walls")) {
    r.fail("gas.front_back_walls", "a 2D case has no front and back walls; set case.dimension = 3");
  }
  const std::string top = r.string("gas.top", "outlet", "top boundary: pressure outlet or wall", {"outlet", "wall"});
  g.boundary.top = top == "outlet" ? TopBoundary::PressureOutlet : TopBoundary::Wall;
  g.boundary.top_pressure = r.number("gas.top_pressure", 0.0, "Pa", "gauge pressure at the outlet");
}


void read_inlet(CaseReader& r, CaseConfig& c, GasKeys& keys) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  const double dx = keys.dx, dz = keys.dz;
  GasConfig& g = c.gas;
  // [inlet]
  g.boundary.inlet_velocity = r.number("inlet.velocity", 1.8, "m/s",
                                       "superficial gas velocity through the whole bottom (the paper: U_mf = 1.8 m/s)");
  g.boundary.ramp_time = r.number("inlet.ramp_time", 0.0, "s", "the background inflow ramps linearly from "
                                  "inlet.ramp_from to inlet.velocity over this time (0: no ramp)", R::non_negative());
  g.boundary.ramp_from = r.number("inlet.ramp_from", 0.0, "m/s", "background inflow at t = 0 when inlet.ramp_time > 0");
  g.boundary.schedule = read_schedule(r, "inlet.", "inlet.velocity", 0.0, true);
  if (g.boundary.schedule.kind == ScheduleKind::Ramp) {
    // The start-up ramp keys, from ramp_start: a ramp that starts at 0 is the start-up ramp itself.
    g.boundary.schedule.ramp_from = g.boundary.ramp_from;
    g.boundary.schedule.ramp_time = g.boundary.ramp_time;
    if (!(g.boundary.ramp_time > 0.0)) r.fail("inlet.ramp_time", "schedule = \"ramp\" needs inlet.ramp_time > 0");
  } else if (g.boundary.schedule.kind != ScheduleKind::Constant) {
    for (const char* k : {"inlet.ramp_from", "inlet.ramp_time"}) {
      if (r.has(k)) r.fail(k, "the start-up ramp is for a constant background; a table schedule can ramp too");
    }
  }
  g.boundary.inlet_noise = r.number("inlet.noise", 0.0, "", "distributor non-uniformity: the background inflow of "
                                    "bottom cell i is scaled by 1 + noise (2u_i - 1), u_i seeded by case.seed, fixed in "
                                    "time, total inflow unchanged", R::Range{0.0, 1.0, false, true});
  g.boundary.noise_seed = c.seed;
  const std::size_t nj = r.table_count("inlet.jet", "jets through the bottom, replacing the background inflow");
  keys.jet_tables = nj;
  g.boundary.jets.clear();
  for (std::size_t k = 0; k < nj; ++k) {
    const std::string p = fmt::format("inlet.jet[{}].", k);
    InletJet j;
    if (three_d) {
      const std::string shape = r.string(p + "shape", "slot", "region of the bottom face (3D only): slot (across the "
                                         "whole depth), rectangle (width x depth) or disc (diameter)",
                                         {"slot", "rectangle", "disc"});
      j.shape = shape == "disc" ? InletShape::Disc : shape == "rectangle" ? InletShape::Rectangle : InletShape::Slot;
    } else {
      for (const char* k : {"shape", "centre_z", "depth", "diameter"}) {
        if (r.has(p + k)) {
          r.fail(p + k, "a 2D case's jet is a slot of the bottom edge (centre, width); shapes across a depth need "
                        "case.dimension = 3");
        }
      }
    }
    j.x_centre = r.number(p + "centre", c.domain.width / 2, "m", "x of the jet centre");
    if (j.shape == InletShape::Disc) {
      if (r.has(p + "width")) r.fail(p + "width", "a disc jet is given by its diameter, not a width");
      j.width = r.number(p + "diameter", std::max(dx, dz), "m", "diameter of a disc jet (3D)", R::positive());
      r.describe_default(p + "diameter", "max(cell_width, cell_depth)");
    } else {
      if (r.has(p + "diameter")) r.fail(p + "diameter", "only a disc jet has a diameter; a slot or a rectangle has a width");
      j.width = r.number(p + "width", dx, "m", "jet width (x extent of a slot or a rectangle)", R::positive());
    }
    if (j.shape == InletShape::Slot) {
      for (const char* k : {"centre_z", "depth"}) {
        if (r.has(p + k)) r.fail(p + k, "a slot spans the whole depth; use shape = \"rectangle\" for a part of it");
      }
      j.z_centre = 0.5 * c.domain.depth;
      j.depth = c.domain.depth;
    } else {
      j.z_centre = r.number(p + "centre_z", 0.5 * c.domain.depth, "m", "z of the centre of a rectangle or disc jet (3D)");
      r.describe_default(p + "centre_z", "domain.depth / 2");
      if (j.shape == InletShape::Rectangle) {
        j.depth = r.number(p + "depth", dz, "m", "z extent of a rectangle jet (3D)", R::positive());
        r.describe_default(p + "depth", "grid.cell_depth");
      } else {
        if (r.has(p + "depth")) r.fail(p + "depth", "a disc jet is given by its diameter; only a rectangle has a depth");
        j.depth = j.width;
      }
    }
    j.velocity = r.number(p + "velocity", 30.0, "m/s", "superficial gas velocity through the jet");
    j.t_start = r.number(p + "start", 0.0, "s", "the jet opens at this time", R::non_negative());
    j.t_end = r.number(p + "end", 0.4, "s", "the jet closes at this time", R::non_negative());
    j.schedule = read_schedule(r, p, p + "velocity", j.t_start, false);
    // The jet is a region of the bottom face: inside it, and wide enough for the grid to resolve.
    if (j.x_centre - 0.5 * j.width < -1e-12 || j.x_centre + 0.5 * j.width > c.domain.width + 1e-12) {
      r.fail(p + "centre", fmt::format("the jet [{}, {}] m is not inside the bottom [0, {}] m",
                                       j.x_centre - 0.5 * j.width, j.x_centre + 0.5 * j.width, c.domain.width));
    }
    if (j.shape != InletShape::Slot &&
        (j.z_centre - 0.5 * j.depth < -1e-12 || j.z_centre + 0.5 * j.depth > c.domain.depth + 1e-12)) {
      r.fail(p + "centre_z", fmt::format("the jet's z range [{}, {}] m is not inside the bottom's depth [0, {}] m",
                                         j.z_centre - 0.5 * j.depth, j.z_centre + 0.5 * j.depth, c.domain.depth));
    }
    const std::string wkey = j.shape == InletShape::Disc ? p + "diameter" : p + "width";
    if (j.width < dx * (1.0 - 1e-9)) {
      r.fail(wkey, fmt::format("{} m is narrower than a gas cell ({} m): the grid cannot resolve it", j.width, dx));
    }
    if (j.shape != InletShape::Slot && j.depth < c.grid.dz * (1.0 - 1e-9)) {
      r.fail(j.shape == InletShape::Disc ? wkey : p + "depth",
             fmt::format("{} m is shallower than a gas cell's depth ({} m): the grid cannot resolve it", j.depth,
                         c.grid.dz));
    }
    if (j.t_end < j.t_start) r.fail(p + "end", "the jet closes before it opens");
    g.boundary.jets.push_back(j);
  }
  read_plates(r, c);
}

// [[inlet.plate]]: blocks of equal holes, each hole a jet appended after the inlet.jet ones.
void read_plates(CaseReader& r, CaseConfig& c) {
  using R = CaseReader;
  const bool three_d = c.domain.dimension == 3;
  GasConfig& g = c.gas;
  const std::size_t np = r.table_count("inlet.plate", "perforated distributor plates: blocks of equal holes (2D slots, "
                                       "3D discs), each hole a jet");
  for (std::size_t k = 0; k < np; ++k) {
    const std::string p = fmt::format("inlet.plate[{}].", k);
    PerforatedPlate pl;
    pl.n_x = static_cast<int>(r.integer(p + "holes", 1, "holes per row (along x)", R::between(1, 100000)));
    if (three_d) {
      pl.n_z = static_cast<int>(r.integer(p + "rows", 1, "rows of holes (along z, 3D)", R::between(1, 100000)));
      pl.hole = r.required_number(p + "hole_diameter", "m", "diameter of each disc hole (3D)", R::positive());
      const std::string lay = r.string(p + "layout", "square", "hole pitch (3D): square or triangular (equilateral, "
                                       "odd rows shifted by half a pitch)", {"square", "triangular"});
      pl.layout = lay == "triangular" ? HolePitch::Triangular : HolePitch::Square;
      pl.z_centre = r.number(p + "centre_z", 0.5 * c.domain.depth, "m", "z of the block's centre (3D)");
      r.describe_default(p + "centre_z", "domain.depth / 2");
    } else {
      for (const char* key : {"rows", "hole_diameter", "layout", "centre_z"}) {
        if (r.has(p + key)) r.fail(p + key, "a 2D plate is a row of slots (holes, hole_width, pitch); set case.dimension = 3");
      }
      pl.hole = r.required_number(p + "hole_width", "m", "width of each slot (2D)", R::positive());
    }
    if (three_d && r.has(p + "hole_width")) r.fail(p + "hole_width", "a 3D plate's holes are discs: hole_diameter");
    pl.pitch = r.required_number(p + "pitch", "m", "centre-to-centre distance of neighbouring holes", R::positive());
    if (pl.pitch < pl.hole) r.fail(p + "pitch", fmt::format("holes of {} m overlap at a pitch of {} m", pl.hole, pl.pitch));
    pl.x_centre = r.number(p + "centre", c.domain.width / 2, "m", "x of the block's centre");
    r.describe_default(p + "centre", "domain.width / 2");
    pl.velocity = r.number(p + "velocity", 10.0, "m/s", "superficial velocity through each hole");
    pl.t_start = r.number(p + "start", 0.0, "s", "the holes open at this time", R::non_negative());
    pl.t_end = r.number(p + "end", 1e9, "s", "the holes close at this time", R::non_negative());
    if (pl.t_end < pl.t_start) r.fail(p + "end", "the plate closes before it opens");
    pl.schedule = read_schedule(r, p, p + "velocity", pl.t_start, false);
    for (const InletJet& h : perforated_plate_holes(pl, three_d ? 3 : 2)) {
      // Holes narrower than a cell are allowed: the face overlap keeps each hole's volume flux exact.
      const double r_x = 0.5 * h.width;
      const double r_z = 0.5 * h.depth;
      if (h.x_centre - r_x < -1e-12 || h.x_centre + r_x > c.domain.width + 1e-12 ||
          (three_d && (h.z_centre - r_z < -1e-12 || h.z_centre + r_z > c.domain.depth + 1e-12))) {
        r.fail(p + "pitch", fmt::format("the hole centred at x = {} m{} is not inside the bottom", h.x_centre,
                                        three_d ? fmt::format(", z = {} m", h.z_centre) : std::string()));
      }
      if (!three_d) {
        InletJet slot = h;
        slot.z_centre = 0.5 * c.domain.depth;
        slot.depth = c.domain.depth;
        g.boundary.jets.push_back(slot);
      } else {
        g.boundary.jets.push_back(h);
      }
    }
  }
}

}  // namespace case_sections
}  // namespace fluidbed
