#pragma once
// The inner product of one line of cells in the order every rank uses: the partition-independent inner products of
// StencilBicgstab and of cg-multigrid's line-sum mode sum each whole line along x with it and add the line sums
// exactly (ExactSum), so only the lines' owners, never their split, could change a bit, and x is never split.

namespace fluidbed {

/// sum u[i] v[i], i < n: four interleaved partial sums from the line's first cell, combined as (s0 + s1) + (s2 + s3),
/// then the tail in order. Cloned for AVX2 without FMA (-ffp-contract=off): every clone rounds alike.
double line_dot(const double* u, const double* v, int n);

}  // namespace fluidbed
