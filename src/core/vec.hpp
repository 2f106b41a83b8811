#pragma once
// Dimension-generic small vectors: Vec<2> and Vec<3> are plain aggregates with named components (x, y[, z]) so
// that they pack into arrays, and with operator[] so that kernels written per axis (template <int d>) can index
// them. Spin<Dim> is the angular velocity: a scalar about z in 2D, a 3-vector in 3D.
#include <cmath>
#include <type_traits>

namespace fluidbed {

template <int Dim>
struct Vec;

template <>
struct Vec<2> {
  static constexpr int dim = 2;
  double x = 0.0;
  double y = 0.0;

  constexpr double& operator[](int a) { return a == 0 ? x : y; }
  constexpr double operator[](int a) const { return a == 0 ? x : y; }
  constexpr Vec& operator+=(Vec o) { x += o.x; y += o.y; return *this; }
  constexpr Vec& operator-=(Vec o) { x -= o.x; y -= o.y; return *this; }
  constexpr Vec& operator*=(double s) { x *= s; y *= s; return *this; }
  friend constexpr Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y}; }
  friend constexpr Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y}; }
  friend constexpr Vec operator-(Vec a) { return {-a.x, -a.y}; }
  friend constexpr Vec operator*(double s, Vec a) { return {s * a.x, s * a.y}; }
  friend constexpr Vec operator*(Vec a, double s) { return {s * a.x, s * a.y}; }
  friend constexpr bool operator==(Vec a, Vec b) = default;
};

template <>
struct Vec<3> {
  static constexpr int dim = 3;
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  constexpr double& operator[](int a) { return a == 0 ? x : (a == 1 ? y : z); }
  constexpr double operator[](int a) const { return a == 0 ? x : (a == 1 ? y : z); }
  constexpr Vec& operator+=(Vec o) { x += o.x; y += o.y; z += o.z; return *this; }
  constexpr Vec& operator-=(Vec o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
  constexpr Vec& operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
  friend constexpr Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend constexpr Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend constexpr Vec operator-(Vec a) { return {-a.x, -a.y, -a.z}; }
  friend constexpr Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
  friend constexpr Vec operator*(Vec a, double s) { return {s * a.x, s * a.y, s * a.z}; }
  friend constexpr bool operator==(Vec a, Vec b) = default;
};

using Vec2 = Vec<2>;
using Vec3 = Vec<3>;

constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
template <int Dim>
constexpr double norm2(Vec<Dim> a) { return dot(a, a); }
template <int Dim>
inline double norm(Vec<Dim> a) { return std::sqrt(dot(a, a)); }

/// Angular velocity (and torque, angular momentum): about z in 2D, a vector in 3D.
template <int Dim>
using Spin = std::conditional_t<Dim == 2, double, Vec3>;

/// z-component of the 3D cross product a x b (a 2D "spin").
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
constexpr Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
/// (0, 0, w) x a: rotation of a by a spin w about z.
constexpr Vec2 cross(double w, Vec2 a) { return {-w * a.y, w * a.x}; }

/// The unit vector of axis a.
template <int Dim>
constexpr Vec<Dim> unit(int a) {
  Vec<Dim> e{};
  e[a] = 1.0;
  return e;
}

}  // namespace fluidbed
