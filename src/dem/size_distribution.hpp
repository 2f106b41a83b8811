#pragma once
// Particle size distributions of one species for the random placement (issue 14, Models item 3): a fixed
// diameter (the paper), uniform, normal or log-normal in diameter between cut-offs, or a list of sizes with their
// fractions. Every distribution here is by number; a list given by mass is turned into number fractions once
// (equal density within a species: n_k ~ m_k / d_k^3).
#include <cstdint>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace fluidbed {

enum class SizeLaw { Fixed, Uniform, Normal, LogNormal, List };

/// Name of a law as the case file spells it: "fixed", "uniform", "normal", "log-normal", "list".
const char* size_law_name(SizeLaw law);

/// Number distribution of the diameter d of one species' particles, m.
struct SizeDistribution {
  SizeLaw law = SizeLaw::Fixed;
  double d_min = 0.0, d_max = 0.0;  ///< cut-offs (uniform: its range), m; Fixed: both the diameter
  double mean = 0.0;   ///< Normal: mean of the untruncated normal, m
  double std = 0.0;    ///< Normal: its standard deviation, m
  double median = 0.0; ///< LogNormal: exp(mu), the median of the untruncated log-normal, m
  double sigma = 0.0;  ///< LogNormal: standard deviation of ln d (dimensionless)
  std::vector<double> diameters{};  ///< List: the sizes, m
  std::vector<double> fractions{};  ///< List: number fractions (sum 1)
};

/// A fixed diameter d.
SizeDistribution fixed_size(double d);

/// Number moments of a distribution: mean <d>, <d^2>, <d^3>, from which d32 = <d^3>/<d^2>.
struct SizeMoments {
  double m1 = 0.0, m2 = 0.0, m3 = 0.0;
  double d32() const { return m3 / m2; }
};
/// The moments of the distribution as requested (truncated where it has cut-offs): closed forms, and quadrature for
/// the normal law (relative error below 1e-10), finite and within the cut-offs however far in a tail they lie.
SizeMoments size_moments(const SizeDistribution& s);

/// Cumulative number fraction of diameters <= d (the truncated distribution's CDF).
double size_cdf(const SizeDistribution& s, double d);

/// One diameter drawn from `s` with a uniform variate u in [0, 1): the inverse of size_cdf (exact for fixed, uniform
/// and list; bisection to round-off for the normal and log-normal laws, so that a sample follows the truncated law,
/// in [d_min, d_max], in any tail).
double size_quantile(const SizeDistribution& s, double u);

/// Natural logarithm of the probability that the untruncated normal or log-normal law puts in [d_min, d_max]
/// (finite where the probability itself underflows); 0 for the other laws.
double size_range_log_mass(const SizeDistribution& s);

/// The least probability of the untruncated law that a range must hold. Below it, the cut-offs lie so far in a
/// tail (a slip of units, a sigma of d given for one of ln d) that the truncated law is an exponential from the
/// cut-off nearer the mode, whatever mean and std (median and sigma) say.
inline constexpr double kMinSizeRangeMass = 1e-12;

/// Why a range is refused: the key at fault (d_min when the range lies above the mode, else d_max) and the message.
struct SizeRangeRefusal {
  std::string key;
  std::string message;
};
/// The refusal of a normal or log-normal law whose [d_min, d_max] holds less than kMinSizeRangeMass of it, naming
/// the keys under `prefix` ("species[0]."); empty for a range worth sampling and for the other laws.
std::optional<SizeRangeRefusal> size_range_refusal(const SizeDistribution& s, const std::string& prefix);

}  // namespace fluidbed
