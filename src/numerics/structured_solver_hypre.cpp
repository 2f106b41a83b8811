#include "numerics/structured_solver_hypre.hpp"

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.hpp"

#ifdef FLUIDBED_HAVE_HYPRE
#include <HYPRE.h>
#include <HYPRE_struct_ls.h>
#include <mpi.h>
#endif

namespace fluidbed {

#ifdef FLUIDBED_HAVE_HYPRE

bool hypre_available() { return true; }

namespace {

// MPI and hypre once per process, finalised at exit, and only if this program started them.
class HypreSession {
 public:
  static void ensure() { static HypreSession session; }

 private:
  HypreSession() {
    int inited = 0;
    MPI_Initialized(&inited);
    if (!inited) {
      int provided = 0;
      MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      own_mpi_ = true;
    }
    HYPRE_Init();
  }
  ~HypreSession() {
    HYPRE_Finalize();
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (own_mpi_ && !finalized) MPI_Finalize();
  }
  bool own_mpi_ = false;
};

constexpr int kMaxIterations = 1000;

template <int Dim>
class HypreStructuredSolver final : public StructuredSolver<Dim> {
  static constexpr int kEntries = 2 * Dim + 1;  // centre, then low and high along each axis

 public:
  HypreStructuredSolver(const Grid<Dim>& grid, double tolerance) : cells_(grid.owned), tol_(tolerance) {
    if (!(grid.owned == grid.domain))
      throw_input_error("pressure correction: the hypre backend solves on one process (owned box = domain)");
    HypreSession::ensure();
    for (int a = 0; a < Dim; ++a) {
      lo_[static_cast<std::size_t>(a)] = cells_.lo[a];
      hi_[static_cast<std::size_t>(a)] = cells_.hi[a] - 1;
    }
    HYPRE_StructGridCreate(MPI_COMM_SELF, Dim, &grid_);
    HYPRE_StructGridSetExtents(grid_, lo_.data(), hi_.data());
    HYPRE_StructGridAssemble(grid_);
    HYPRE_StructStencilCreate(Dim, kEntries, &stencil_);
    for (int e = 0; e < kEntries; ++e) {
      std::array<int, Dim> off{};
      if (e > 0) off[static_cast<std::size_t>((e - 1) / 2)] = (e - 1) % 2 == 0 ? -1 : 1;
      HYPRE_StructStencilSetElement(stencil_, e, off.data());
    }
    HYPRE_StructMatrixCreate(MPI_COMM_SELF, grid_, stencil_, &a_);
    HYPRE_StructMatrixInitialize(a_);
    HYPRE_StructVectorCreate(MPI_COMM_SELF, grid_, &b_);
    HYPRE_StructVectorInitialize(b_);
    HYPRE_StructVectorCreate(MPI_COMM_SELF, grid_, &x_);
    HYPRE_StructVectorInitialize(x_);
    const std::size_t n = cells_.count();
    values_.resize(n * kEntries);
    rhs_.resize(n);
    sol_.resize(n);
    for (int e = 0; e < kEntries; ++e) entries_[static_cast<std::size_t>(e)] = e;
  }
  ~HypreStructuredSolver() override {
    destroy_solver();
    HYPRE_StructVectorDestroy(x_);
    HYPRE_StructVectorDestroy(b_);
    HYPRE_StructMatrixDestroy(a_);
    HYPRE_StructStencilDestroy(stencil_);
    HYPRE_StructGridDestroy(grid_);
  }
  HypreStructuredSolver(const HypreStructuredSolver&) = delete;
  HypreStructuredSolver& operator=(const HypreStructuredSolver&) = delete;

  const char* name() const override { return "hypre-pfmg"; }
  void set_tolerance(double relative) override {
    tol_ = relative;
    if (solver_) HYPRE_StructPCGSetTol(solver_, tol_);
  }

  void solve(const FaceFields<Dim>& coeff, const Field<Dim>& rhs, Field<Dim>& x, bool reuse_factorisation) override {
    const bool has_boundary = couples_to_boundary(cells_, coeff);
    // As the Eigen backend: an all-Neumann problem pins its first cell to zero symmetrically.
    const bool pin = !has_boundary;
    std::size_t r = 0;  // hypre's box order: axis 0 fastest, as for_each runs
    for_each(cells_, [&](const Index<Dim>& c) {
      double* v = values_.data() + r * kEntries;
      double diag = 0.0;
      for (int a = 0; a < Dim; ++a) {
        const double lo = coeff[a][c];
        const double hi = coeff[a][shifted<Dim>(c, a, 1)];
        if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(rhs[c]))
          throw_simulation_error("gas pressure correction (hypre): a face coefficient or the imbalance is not finite");
        diag += lo + hi;
        // A boundary face couples to zero beyond the box: its coefficient stays on the diagonal only.
        v[1 + 2 * a] = c[a] > cells_.lo[a] ? -lo : 0.0;
        v[2 + 2 * a] = c[a] < cells_.hi[a] - 1 ? -hi : 0.0;
      }
      double rb = rhs[c];
      if (pin) {
        if (c == cells_.lo) {
          for (int e = 1; e < kEntries; ++e) v[e] = 0.0;
          diag = 1.0;
          rb = 0.0;
        } else {
          for (int a = 0; a < Dim; ++a)
            if (c == shifted<Dim>(cells_.lo, a, 1)) v[1 + 2 * a] = 0.0;
        }
      }
      if (!(diag > 0.0)) diag = 1.0;  // a cell with no open face: p' is free, keep it at zero
      v[0] = diag;
      rhs_[r] = rb;
      sol_[r] = x[c];
      ++r;
    });
    HYPRE_StructMatrixSetBoxValues(a_, lo_.data(), hi_.data(), kEntries, entries_.data(), values_.data());
    HYPRE_StructMatrixAssemble(a_);
    HYPRE_StructVectorSetBoxValues(b_, lo_.data(), hi_.data(), rhs_.data());
    HYPRE_StructVectorAssemble(b_);
    HYPRE_StructVectorSetBoxValues(x_, lo_.data(), hi_.data(), sol_.data());
    HYPRE_StructVectorAssemble(x_);
    if (!reuse_factorisation || !solver_) setup();
    HYPRE_StructPCGSolve(solver_, a_, b_, x_);
    double res = 0.0;
    HYPRE_StructPCGGetFinalRelativeResidualNorm(solver_, &res);
    HYPRE_StructVectorGetBoxValues(x_, lo_.data(), hi_.data(), sol_.data());
    if (!(res <= tol_) && reuse_factorisation) {
      // The kept hierarchy no longer suits the matrix: set it up anew once.
      setup();
      HYPRE_StructPCGSolve(solver_, a_, b_, x_);
      HYPRE_StructPCGGetFinalRelativeResidualNorm(solver_, &res);
      HYPRE_StructVectorGetBoxValues(x_, lo_.data(), hi_.data(), sol_.data());
    }
    HYPRE_ClearAllErrors();
    bool finite = true;
    for (double s : sol_) finite = finite && std::isfinite(s);
    if (!finite || !(res <= tol_)) {
      int its = 0;
      HYPRE_StructPCGGetNumIterations(solver_, &its);
      throw_simulation_error("gas pressure correction (hypre PFMG-CG): relative residual " + std::to_string(res) +
                             " after " + std::to_string(its) + " iterations");
    }
    r = 0;
    for_each(cells_, [&](const Index<Dim>& c) { x[c] = sol_[r++]; });
  }

  /// Iterations of the last solve (for benchmarks).
  int iterations() const {
    int its = 0;
    if (solver_) HYPRE_StructPCGGetNumIterations(solver_, &its);
    return its;
  }

 private:
  void destroy_solver() {
    if (solver_) HYPRE_StructPCGDestroy(solver_);
    if (precond_) HYPRE_StructPFMGDestroy(precond_);
    solver_ = nullptr;
    precond_ = nullptr;
  }
  void setup() {
    destroy_solver();
    HYPRE_StructPCGCreate(MPI_COMM_SELF, &solver_);
    HYPRE_StructPCGSetTol(solver_, tol_);
    HYPRE_StructPCGSetTwoNorm(solver_, 1);
    HYPRE_StructPCGSetRelChange(solver_, 0);
    HYPRE_StructPCGSetMaxIter(solver_, kMaxIterations);
    HYPRE_StructPFMGCreate(MPI_COMM_SELF, &precond_);
    HYPRE_StructPFMGSetMaxIter(precond_, 1);
    HYPRE_StructPFMGSetTol(precond_, 0.0);
    HYPRE_StructPFMGSetZeroGuess(precond_);
    HYPRE_StructPFMGSetRAPType(precond_, 0);     // Galerkin coarse operators
    HYPRE_StructPFMGSetRelaxType(precond_, 2);   // symmetric red-black Gauss-Seidel (keeps CG's symmetry)
    HYPRE_StructPFMGSetNumPreRelax(precond_, 1);
    HYPRE_StructPFMGSetNumPostRelax(precond_, 1);
    HYPRE_StructPFMGSetSkipRelax(precond_, 0);
    HYPRE_StructPCGSetPrecond(solver_, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, precond_);
    HYPRE_StructPCGSetup(solver_, a_, b_, x_);
  }

  IndexBox<Dim> cells_;
  double tol_;
  std::array<int, Dim> lo_{}, hi_{};
  std::array<int, kEntries> entries_{};
  HYPRE_StructGrid grid_ = nullptr;
  HYPRE_StructStencil stencil_ = nullptr;
  HYPRE_StructMatrix a_ = nullptr;
  HYPRE_StructVector b_ = nullptr, x_ = nullptr;
  HYPRE_StructSolver solver_ = nullptr, precond_ = nullptr;
  std::vector<double> values_, rhs_, sol_;
};

}  // namespace

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_hypre_structured_solver(const Grid<Dim>& grid, double tolerance) {
  return std::make_unique<HypreStructuredSolver<Dim>>(grid, tolerance);
}

#else

bool hypre_available() { return false; }

template <int Dim>
std::unique_ptr<StructuredSolver<Dim>> make_hypre_structured_solver(const Grid<Dim>&, double) {
  throw_input_error("gas.pressure_solver = \"hypre-pfmg\": this build has no hypre (install libhypre-dev and "
                    "configure again)");
}

#endif

template std::unique_ptr<StructuredSolver<2>> make_hypre_structured_solver(const Grid<2>&, double);
template std::unique_ptr<StructuredSolver<3>> make_hypre_structured_solver(const Grid<3>&, double);

}  // namespace fluidbed
