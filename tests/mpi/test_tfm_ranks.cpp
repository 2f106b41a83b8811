// The two-fluid model on 1 to 4 ranks (ctest runs this under mpiexec -n 1..4) against one process, bit for bit:
// every array of the state after a jet has set the bed moving, the monitors of every step (solids mass, pressure
// drop, smallest voidage, largest solids speed, gas continuity residual, Theta), in 2D and 3D, walled and periodic,
// and a state saved on one process continued on every rank count. Each rank also runs the one-process reference.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "tfm/tfm_solver.hpp"
#include "mpi_world.hpp"

namespace fluidbed::tfm {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// A bed of 0.2 x 0.4 m (10 x 20 cells) with a jet, the multigrid pressure backend (the one that runs on ranks).
TfmConfig jet_bed(int dimension, bool periodic) {
  TfmConfig c;
  c.domain.width = 0.2;
  c.domain.height = 0.4;
  c.packed_height = 0.2;
  c.pressure_solver = PressureBackend::CgMultigrid;
  InletJet jet{periodic ? 0.03 : 0.1, 0.04, 20.0, 0.0, 1.0};
  if (dimension == 3) {
    c.domain.dimension = 3;
    c.domain.depth = 0.08;
    c.domain.gravity = {0.0, -9.81, 0.0};
    jet.shape = InletShape::Rectangle;
    jet.z_centre = periodic ? 0.03 : 0.04;
    jet.depth = 0.04;
  }
  c.domain.periodic = {periodic, false, periodic && dimension == 3};
  c.boundary.jets = {jet};
  return c;
}

template <int Dim>
std::vector<double> monitors(const TfmSolver<Dim>& s) {
  return {s.time(), s.solids_mass(), s.pressure_drop(), s.min_voidage(), s.max_solids_speed(),
          s.gas_volume_residual(), s.bed_granular_temperature_max(), s.solids_mean_granular_temperature()};
}

template <int Dim>
void expect_same_state(const TfmSolver<Dim>& one, const TfmSolver<Dim>& many, const std::string& what) {
  const std::vector<NamedArray> a = one.save_state(), b = many.save_state();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].values.size(), b[k].values.size()) << a[k].name;
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a[k].values.size(); ++i) differ += bits(a[k].values[i]) != bits(b[k].values[i]);
    EXPECT_EQ(differ, 0u) << what << ", " << world().size() << " ranks: array " << a[k].name;
  }
}

template <int Dim>
void check(const TfmConfig& c, double t_end) {
  TfmSolver<Dim> one(c, serial_comm()), many(c, world());
  int step = 0;
  while (one.time() < t_end - 1e-12) {
    one.step(t_end);
    many.step(t_end);
    const std::vector<double> m1 = monitors(one), mn = monitors(many);
    for (std::size_t k = 0; k < m1.size(); ++k)
      ASSERT_EQ(bits(m1[k]), bits(mn[k])) << "monitor " << k << " at step " << step << " on " << world().size() << " ranks";
    ++step;
  }
  EXPECT_GT(one.max_solids_speed(), 1e-2);  // the jet has set the bed moving
  expect_same_state(one, many, "after " + std::to_string(step) + " steps");
}

TEST(TfmRanks, JetBed2d) { check<2>(jet_bed(2, false), 0.03); }
TEST(TfmRanks, PeriodicJetBed2d) { check<2>(jet_bed(2, true), 0.03); }
TEST(TfmRanks, JetBed3d) { check<3>(jet_bed(3, false), 0.02); }
TEST(TfmRanks, PeriodicCornerJet3d) { check<3>(jet_bed(3, true), 0.02); }

TEST(TfmRanks, StateOfOneProcessContinuesOnEveryRankCount) {
  const TfmConfig c = jet_bed(3, false);
  TfmSolver<3> one(c, serial_comm());
  one.advance_to(0.01);
  const std::vector<NamedArray> saved = one.save_state();
  one.advance_to(0.02);
  TfmSolver<3> many(c, world());
  many.restore_state(saved);
  many.advance_to(0.02);
  expect_same_state(one, many, "continued");
}

TEST(TfmRanks, RefusesABackendThatDependsOnTheRanks) {
  if (world().size() == 1) GTEST_SKIP() << "one rank takes every backend";
  TfmConfig c = jet_bed(2, false);
  c.pressure_solver = PressureBackend::Eigen;
  try {
    TfmSolver<2> s(c, world());
    FAIL() << "the Cholesky backend was accepted on several ranks";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cg-multigrid"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fluidbed::tfm
