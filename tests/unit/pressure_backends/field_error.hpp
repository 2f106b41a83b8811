#pragma once
// The error measures of the pressure-backend tests: largest magnitude of a field and largest difference of two
// fields over every stored entry.
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/field.hpp"

namespace fluidbed::test {

template <int Dim>
double max_abs(const Field<Dim>& f) {
  double m = 0.0;
  for (double v : f.data()) m = std::max(m, std::abs(v));
  return m;
}

template <int Dim>
double max_diff(const Field<Dim>& a, const Field<Dim>& b) {
  double m = 0.0;
  for (std::size_t k = 0; k < a.data().size(); ++k) m = std::max(m, std::abs(a.data()[k] - b.data()[k]));
  return m;
}

}  // namespace fluidbed::test
