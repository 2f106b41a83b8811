#pragma once
// The choice of contact law (one name per part, as in the case file's [contact] keys), its parameters beyond the
// paper's, the one dispatch from the names to a ContactLaw type, and the Hertz impact in closed or
// once-integrated form that the Tsuji damping and the time-step check need.
#include <string>
#include <utility>
#include <vector>

#include "dem/contact_law.hpp"

namespace fluidbed {

enum class NormalModel { Linear, Hertz };
enum class DampingModel { Paper, Tsuji };
enum class TangentialModel { Linear, Mindlin };
enum class RollingModel { None, Constant, Epsd };

/// Elastic constants of a material (a species or the walls), for Hertz and Mindlin.
struct ElasticMaterial {
  double youngs_modulus = 7e10;  ///< E, Pa (default: glass)
  double poisson_ratio = 0.25;   ///< nu
};

/// Which part of each kind the contact law is made of; the defaults are the paper's law.
struct ContactModelConfig {
  NormalModel normal = NormalModel::Linear;
  DampingModel damping = DampingModel::Paper;
  TangentialModel tangential = TangentialModel::Linear;
  RollingModel rolling = RollingModel::None;
  /// Rolling dashpot damping ratio eta_r of the elastic-plastic model (Ai et al. 2011 use 0.3).
  double rolling_damping = 0.3;
  /// Impact speed at which a Hertz contact's duration is judged (time step default and check), m/s.
  double impact_speed = 1.0;
  /// The walls' material (Hertz, Mindlin).
  ElasticMaterial wall_material{};

  bool needs_rolling_history() const { return rolling == RollingModel::Epsd; }
};

const char* to_string(NormalModel m);
const char* to_string(DampingModel m);
const char* to_string(TangentialModel m);
const char* to_string(RollingModel m);
/// The names the case file accepts, in enum order.
inline const std::vector<std::string>& normal_model_names() {
  static const std::vector<std::string> v{"linear", "hertz"};
  return v;
}
inline const std::vector<std::string>& damping_model_names() {
  static const std::vector<std::string> v{"paper", "tsuji"};
  return v;
}
inline const std::vector<std::string>& tangential_model_names() {
  static const std::vector<std::string> v{"linear", "mindlin"};
  return v;
}
inline const std::vector<std::string>& rolling_model_names() {
  static const std::vector<std::string> v{"none", "constant", "epsd"};
  return v;
}

/// 1/E* = (1 - nu_a^2) / E_a + (1 - nu_b^2) / E_b (Hertz); a wall is the material b.
double effective_youngs_modulus(const ElasticMaterial& a, const ElasticMaterial& b);
/// 1/G* = 2 (2 - nu_a)(1 + nu_a) / E_a + 2 (2 - nu_b)(1 + nu_b) / E_b (Mindlin, with G = E / (2 (1 + nu))).
double effective_shear_modulus(const ElasticMaterial& a, const ElasticMaterial& b);

/// Restitution of a Hertz impact with Tsuji damping eta_n = alpha sqrt(m* dF/d delta): the dimensionless
/// equation X'' = -X^(3/2) - alpha sqrt(3/2) X^(1/4) X' (X = delta / L, L = (m* v^2 / K)^(2/5), K = (4/3) E*
/// sqrt(R*)) has no speed left, so e depends on alpha alone. Integrated by RK4 (3 10^4 steps per contact).
double hertz_tsuji_restitution(double alpha);
/// The alpha that gives restitution e (bisection on hertz_tsuji_restitution to 1e-10).
double tsuji_alpha_for_hertz(double e);
/// The alpha of Tsuji damping on a linear spring: Eq. 8 written as eta = alpha sqrt(m* k).
double tsuji_alpha_for_linear(double e);

/// Elastic Hertz impact of two bodies closing at speed v (Johnson 1985, sec. 11.4): the largest overlap
/// delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5) and the contact duration
/// t_c = 2 (delta_max / v) int_0^1 (1 - x^(5/2))^(-1/2) dx = 2.9432 delta_max / v.
struct HertzImpact {
  double max_overlap;  ///< m
  double duration;     ///< s
};
HertzImpact hertz_impact(double m_eff, double e_star, double r_eff, double v);

/// Call f(Law{}) with the ContactLaw type that `c` names: the one switch from names to a law, outside any loop.
template <class F>
decltype(auto) with_contact_law(const ContactModelConfig& c, F&& f) {
  auto rolling = [&]<class N, class D, class T>() -> decltype(auto) {
    switch (c.rolling) {
      case RollingModel::Constant: return f(ContactLaw<N, D, T, ConstantRolling>{});
      case RollingModel::Epsd: return f(ContactLaw<N, D, T, EpsdRolling>{});
      case RollingModel::None: break;
    }
    return f(ContactLaw<N, D, T, NoRolling>{});
  };
  auto tangential = [&]<class N, class D>() -> decltype(auto) {
    if (c.tangential == TangentialModel::Mindlin) return rolling.template operator()<N, D, MindlinTangential>();
    return rolling.template operator()<N, D, LinearTangential>();
  };
  // The damping goes with the spring it is derived for: the paper's with the linear spring, Tsuji's with
  // either (the loader rejects paper damping on a Hertz spring).
  if (c.normal == NormalModel::Hertz) return tangential.template operator()<HertzNormal, TsujiDamping>();
  if (c.damping == DampingModel::Tsuji) return tangential.template operator()<LinearNormal, TsujiDamping>();
  return tangential.template operator()<LinearNormal, PaperDamping>();
}

}  // namespace fluidbed
