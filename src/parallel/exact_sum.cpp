#include "parallel/exact_sum.hpp"

#include <bit>
#include <cmath>
#include <limits>

namespace fluidbed {

namespace {

constexpr std::int64_t kLimbMask = 0xffffffffLL;
constexpr int kUnitExponent = -1074;  // limb 0, bit 0: the smallest subnormal

}  // namespace

void ExactSum::add(double x) {
  // Branch-free but for NaN and infinities (rare, so predicted): a zero adds zero limbs, the sign is applied as a
  // mask, and the limb index and shift come from the exponent by shifts. A branch on the sign or on zero is taken
  // at random in a sum of mixed terms and cost ~8 ns a term in mispredictions (bench_mpi_costs).
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const auto biased = static_cast<unsigned>((bits >> 52) & 0x7ff);
  if (biased == 0x7ff) [[unlikely]] {
    if (std::isnan(x)) {
      ++nan_;
    } else {
      ++(x > 0.0 ? pos_inf_ : neg_inf_);
    }
    return;
  }
  // x = +-m 2^(b - 1074): the integer significand m (53 bits, fewer for a subnormal) and its bit offset b.
  const std::uint64_t normal = biased != 0 ? 1 : 0;
  const std::uint64_t m = (bits & ((std::uint64_t{1} << 52) - 1)) | (normal << 52);
  const unsigned b = biased - static_cast<unsigned>(normal);
  const std::size_t k = b >> 5;
  const unsigned __int128 v = static_cast<unsigned __int128>(m) << (b & 31);
  const auto sign = -static_cast<std::int64_t>(bits >> 63);  // 0 or -1: (c ^ sign) - sign is c or -c
  const auto lo = static_cast<std::int64_t>(static_cast<std::uint64_t>(v) & kLimbMask);
  const auto mid = static_cast<std::int64_t>(static_cast<std::uint64_t>(v >> 32) & kLimbMask);
  const auto hi = static_cast<std::int64_t>(static_cast<std::uint64_t>(v >> 64));
  limb_[k] += (lo ^ sign) - sign;
  limb_[k + 1] += (mid ^ sign) - sign;
  limb_[k + 2] += (hi ^ sign) - sign;
  if (++pending_ >= (1 << 30)) [[unlikely]] normalise();
}

void ExactSum::normalise() {
  for (std::size_t k = 0; k + 1 < limb_.size(); ++k) {
    const std::int64_t carry = limb_[k] >> 32;  // floor division by 2^32, also for a negative limb
    limb_[k] &= kLimbMask;
    limb_[k + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::merge(const ExactSum& other) {
  ExactSum o = other;
  o.normalise();
  normalise();
  for (std::size_t k = 0; k < limb_.size(); ++k) limb_[k] += o.limb_[k];
  nan_ += o.nan_;
  pos_inf_ += o.pos_inf_;
  neg_inf_ += o.neg_inf_;
  pending_ = 1;  // each limb now below 2^33: as after two additions
}

double ExactSum::value() const {
  if (nan_ > 0 || (pos_inf_ > 0 && neg_inf_ > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (pos_inf_ > 0) return std::numeric_limits<double>::infinity();
  if (neg_inf_ > 0) return -std::numeric_limits<double>::infinity();
  ExactSum s = *this;
  s.normalise();
  std::array<std::int64_t, kLimbs>& l = s.limb_;
  const bool negative = l.back() < 0;
  if (negative) {
    for (std::int64_t& x : l) x = -x;
    s.normalise();
  }
  const double sign = negative ? -1.0 : 1.0;
  if (l.back() != 0) return sign * std::numeric_limits<double>::infinity();  // beyond 2^1070
  int h = kLimbs - 2;
  while (h >= 0 && l[static_cast<std::size_t>(h)] == 0) --h;
  if (h < 0) return 0.0;
  const int top_bit = 32 * h + 31 - std::countl_zero(static_cast<std::uint32_t>(l[static_cast<std::size_t>(h)]));
  const int start = top_bit - 63;  // the 64 bits [start, top_bit] hold the 53 kept, the rounding bit and more
  if (start <= 0) {
    // Below 2^64 units: converting the integer rounds once; scaling by 2^-1074 is then exact (a result under
    // 2^53 units, a subnormal, is exact already).
    const auto n = static_cast<std::uint64_t>(l[0]) | (static_cast<std::uint64_t>(l[1]) << 32);
    return sign * std::ldexp(static_cast<double>(n), kUnitExponent);
  }
  const auto k0 = static_cast<std::size_t>(start / 32);
  const int s0 = start % 32;
  unsigned __int128 window = 0;
  for (std::size_t i = 0; i < 3 && k0 + i < l.size(); ++i) {
    window |= static_cast<unsigned __int128>(static_cast<std::uint64_t>(l[k0 + i])) << (32 * i);
  }
  auto top = static_cast<std::uint64_t>(window >> s0);
  // Any set bit below the window only breaks a tie: folded into bit 0, eleven places under the rounding bit, it
  // makes the conversion round as the exact value would.
  bool sticky = (static_cast<std::uint64_t>(l[k0]) & ((std::uint64_t{1} << s0) - 1)) != 0;
  for (std::size_t k = 0; k < k0 && !sticky; ++k) sticky = l[k] != 0;
  if (sticky) top |= 1;
  return sign * std::ldexp(static_cast<double>(top), start + kUnitExponent);
}

std::array<std::int64_t, ExactSum::kWords> ExactSum::words() const {
  ExactSum s = *this;
  s.normalise();
  std::array<std::int64_t, kWords> w{};
  for (std::size_t k = 0; k < s.limb_.size(); ++k) w[k] = s.limb_[k];
  w[kLimbs] = s.nan_;
  w[kLimbs + 1] = s.pos_inf_;
  w[kLimbs + 2] = s.neg_inf_;
  return w;
}

ExactSum ExactSum::from_words(std::span<const std::int64_t, kWords> w) {
  ExactSum s;
  for (std::size_t k = 0; k < s.limb_.size(); ++k) s.limb_[k] = w[k];
  s.nan_ = w[kLimbs];
  s.pos_inf_ = w[kLimbs + 1];
  s.neg_inf_ = w[kLimbs + 2];
  s.normalise();
  return s;
}

double exact_sum(std::span<const double> values) {
  ExactSum s;
  for (double x : values) s.add(x);
  return s.value();
}

}  // namespace fluidbed
