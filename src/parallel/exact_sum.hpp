#pragma once
// A sum of doubles that does not depend on the order or the grouping of its terms: the reduction that keeps a
// result the same bits on any number of threads and ranks. Every finite double is an integer multiple of 2^-1074
// below 2^1024, so the exact sum is an integer in units of 2^-1074; it is held in 32-bit limbs of int64 (the
// fixed-point "long accumulator" of Kulisch, Computer Arithmetic and Validity, 2013, ch. 8), added exactly and
// rounded once, to nearest with ties to even. Integer addition is associative, so partial accumulators merge
// (merge, or an MPI integer sum of limbs()) in any order to the same state after normalise().
#include <array>
#include <cstdint>
#include <span>

namespace fluidbed {

class ExactSum {
 public:
  /// Limb k weighs 2^(32 k - 1074); 66 limbs reach 2^1038, two more hold the carries of sums beyond DBL_MAX.
  static constexpr int kLimbs = 68;

  ExactSum() = default;
  explicit ExactSum(double x) { add(x); }

  /// Adds x exactly. NaN and infinities are remembered and returned by value() as IEEE addition would (NaN,
  /// or inf - inf = NaN).
  void add(double x);
  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  /// Adds another accumulator's terms, exactly.
  void merge(const ExactSum& other);

  /// The sum rounded to the nearest double (ties to even); +0 for an empty or cancelling sum, +-inf beyond the
  /// largest double.
  double value() const;

  /// Carries propagated, every limb but the last in [0, 2^32): the canonical state, the same for every order of
  /// the same terms. A reduction over processes sums the limbs of normalised accumulators (each limb then stays
  /// below 2^63 for up to 2^31 of them) and normalises the result.
  void normalise();
  /// The limbs and the special-value counts as one array of integers (for an MPI sum), and back.
  static constexpr int kWords = kLimbs + 3;
  std::array<std::int64_t, kWords> words() const;
  static ExactSum from_words(std::span<const std::int64_t, kWords> w);

 private:
  std::array<std::int64_t, kLimbs> limb_{};
  std::int64_t nan_ = 0, pos_inf_ = 0, neg_inf_ = 0;
  std::int32_t pending_ = 0;  // additions since the last normalisation: each moves a limb by less than 2^32
};

/// The exact sum of values, rounded once (the same bits for any order of the values).
double exact_sum(std::span<const double> values);

}  // namespace fluidbed
