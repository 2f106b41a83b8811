#pragma once
// A sparse matrix whose pattern (at most five entries per row: self, W, E, S, N) is fixed once, so repeated
// assemblies write values in place and factorisations can reuse their symbolic analysis.
#include <array>
#include <vector>

#include <Eigen/SparseCore>

namespace fluidbed {

/// Loops over fewer cells than this run serially: thread start-up would cost more than the work.
inline constexpr int kParallelCells = 16384;

class StencilMatrix {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
  static constexpr int kSlots = 5;  ///< slot 0 is the diagonal, 1..4 the neighbours in the order given

  /// neighbours[row] lists up to four column indices; -1 where there is none.
  void build(int n, const std::vector<std::array<int, 4>>& neighbours);
  /// The cell-centred five-point pattern of an nx x ny grid, rows numbered i fastest (Grid2::index), neighbours
  /// in the order W, E, S, N.
  void build_cells(int nx, int ny);

  int rows() const { return static_cast<int>(offset_.size() / kSlots); }
  /// Writes one row: diagonal and the four neighbour coefficients (ignored where the neighbour is -1).
  void set_row(int row, double diag, const std::array<double, 4>& off) {
    double* val = matrix_.valuePtr();
    const int* o = &offset_[static_cast<std::size_t>(row) * kSlots];
    val[o[0]] = diag;
    for (int k = 0; k < 4; ++k)
      if (o[k + 1] >= 0) val[o[k + 1]] = off[static_cast<std::size_t>(k)];
  }
  const Matrix& matrix() const { return matrix_; }

 private:
  Matrix matrix_;
  std::vector<int> offset_;
};

}  // namespace fluidbed
