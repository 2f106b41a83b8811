// ExactSum: the exact sum rounded once, whatever the order and grouping of its terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "parallel/exact_sum.hpp"

namespace fluidbed {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Terms of every magnitude and both signs, with heavy cancellation: a naive sum depends on their order.
std::vector<double> wild_terms(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-60, 60);
  std::vector<double> v(n);
  for (double& x : v) x = std::ldexp(mant(rng), expo(rng));
  return v;
}

TEST(ExactSum, CancellationThatNaiveSumsLose) {
  EXPECT_EQ(exact_sum(std::vector<double>{1e100, 1.0, -1e100}), 1.0);
  EXPECT_EQ(exact_sum(std::vector<double>{1.0, 1e-300, -1.0}), 1e-300);
  // The doubles 0.1 + 0.2 - 0.3 sum to 2^-55 exactly; left to right in doubles they give 2^-54.
  EXPECT_EQ(exact_sum(std::vector<double>{0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
  // The smallest subnormal survives next to the largest double.
  const double tiny = std::numeric_limits<double>::denorm_min(), big = std::numeric_limits<double>::max();
  EXPECT_EQ(exact_sum(std::vector<double>{big, tiny, -big}), tiny);
  EXPECT_EQ(exact_sum(std::vector<double>{}), 0.0);
  EXPECT_EQ(exact_sum(std::vector<double>{-2.5}), -2.5);
}

TEST(ExactSum, RoundsOnceToNearestWithTiesToEven) {
  const double two53 = 9007199254740992.0;  // 2^53: the spacing of doubles there is 2
  EXPECT_EQ(exact_sum(std::vector<double>{two53, 1.0}), two53);            // a tie: to the even neighbour
  EXPECT_EQ(exact_sum(std::vector<double>{two53, 3.0}), two53 + 4.0);      // a tie: to the even neighbour
  EXPECT_EQ(exact_sum(std::vector<double>{two53, 1.0, 1e-30}), two53 + 2.0);  // above the tie by a hair: up
  EXPECT_EQ(exact_sum(std::vector<double>{two53, 1.0, -1e-30}), two53);       // below it: down
  EXPECT_EQ(exact_sum(std::vector<double>{-two53, -1.0, -1e-30}), -two53 - 2.0);
  // 0.1 + 0.2 exactly is 0.30000000000000001665..., nearest double 0.30000000000000004 (what IEEE addition gives).
  EXPECT_EQ(exact_sum(std::vector<double>{0.1, 0.2}), 0.1 + 0.2);
}

TEST(ExactSum, SpecialValuesAsIeeeAddition) {
  const double inf = std::numeric_limits<double>::infinity(), big = std::numeric_limits<double>::max();
  EXPECT_EQ(exact_sum(std::vector<double>{big, big}), inf);
  EXPECT_EQ(exact_sum(std::vector<double>{-big, -big, 1.0}), -inf);
  EXPECT_EQ(exact_sum(std::vector<double>{big, big, -big}), big);  // no overflow in between: exact
  EXPECT_EQ(exact_sum(std::vector<double>{inf, 1.0}), inf);
  EXPECT_TRUE(std::isnan(exact_sum(std::vector<double>{inf, -inf})));
  EXPECT_TRUE(std::isnan(exact_sum(std::vector<double>{1.0, std::nan("")})));
}

TEST(ExactSum, SameBitsForEveryOrderAndGrouping) {
  std::vector<double> v = wild_terms(20000, 7);
  const double reference = exact_sum(v);
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(v.begin(), v.end(), rng);
    EXPECT_EQ(bits(exact_sum(v)), bits(reference));
    // Split into a random number of parts, each accumulated alone, merged in a random order; also through words().
    std::uniform_int_distribution<std::size_t> parts_of(2, 40);
    std::vector<ExactSum> parts(parts_of(rng));
    std::uniform_int_distribution<std::size_t> which(0, parts.size() - 1);
    for (double x : v) parts[which(rng)].add(x);
    std::shuffle(parts.begin(), parts.end(), rng);
    ExactSum merged;
    for (const ExactSum& p : parts) merged.merge(p);
    EXPECT_EQ(bits(merged.value()), bits(reference));
    std::array<std::int64_t, ExactSum::kWords> total{};
    for (const ExactSum& p : parts) {
      const auto w = p.words();
      for (std::size_t k = 0; k < w.size(); ++k) total[k] += w[k];
    }
    EXPECT_EQ(bits(ExactSum::from_words(total).value()), bits(reference));
  }
}

TEST(ExactSum, AgreesWithIntegerArithmeticOnScaledIntegers) {
  // Multiples of 2^-20 below 2^30: their exact sum is an integer multiple of 2^-20 that __int128 holds exactly.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<std::int64_t> units(-(std::int64_t{1} << 50), std::int64_t{1} << 50);
  std::vector<double> v;
  __int128 exact = 0;
  for (int k = 0; k < 100000; ++k) {
    const std::int64_t u = units(rng);
    exact += u;
    v.push_back(std::ldexp(static_cast<double>(u), -20));
  }
  // The integer converted once (round to nearest), then scaled by a power of two: the correctly rounded sum.
  const double expected = std::ldexp(static_cast<double>(exact), -20);
  EXPECT_EQ(bits(exact_sum(v)), bits(expected));
}

TEST(ExactSum, EveryExponentAndSignLandsInItsLimbs) {
  // Each term alone comes back exactly, and with its negation cancels to +0, from the smallest subnormal to the
  // largest double: the limb index, the shift and the sign of every exponent (the add path has no branch on them).
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::uint64_t> fraction(0, (std::uint64_t{1} << 52) - 1);
  for (std::uint64_t biased = 0; biased < 0x7ff; ++biased) {
    for (const std::uint64_t f : {std::uint64_t{0}, std::uint64_t{1}, fraction(rng), (std::uint64_t{1} << 52) - 1}) {
      for (const std::uint64_t sign : {std::uint64_t{0}, std::uint64_t{1}}) {
        const double x = std::bit_cast<double>(sign << 63 | biased << 52 | f);
        ExactSum one(x);
        // -0 alone sums to +0, as IEEE addition of +0 and -0 does.
        EXPECT_EQ(bits(one.value()), bits(x == 0.0 ? 0.0 : x)) << biased << " " << f << " " << sign;
        one.add(-x);
        EXPECT_EQ(bits(one.value()), bits(0.0)) << biased << " " << f << " " << sign;
      }
    }
  }
}

}  // namespace
}  // namespace fluidbed
