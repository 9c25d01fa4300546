#pragma once
// Forward-mode differentiation in two variables (x, y) to second order, for writing a
// sag formula once and getting its gradient and Hessian exactly. Eigen's AutoDiffScalar
// gives first derivatives only (nesting it for the Hessian allocates); the sag formulas
// need a fixed-size second-order type on the hot path.
//
// Jet<1> carries value and gradient; Jet<2> adds the Hessian (xx, xy, yy).

#include <cmath>

namespace freeturn {

namespace detail {
// The Hessian's part of a jet: none in Jet<1>, so that a first-order jet is three doubles
// (the planner evaluates designs through Jet<1>, JetSurface::sag_gradient, and copied an
// unused Hessian with every operation). The arithmetic is the same either way.
template <int Order>
struct JetSecond {
  double dxx, dxy, dyy;
};
template <>
struct JetSecond<1> {};
}  // namespace detail

template <int Order>
struct Jet : detail::JetSecond<Order> {
  static_assert(Order == 1 || Order == 2);
  double v;
  double dx, dy;

  // Uninitialised, as a double is: formulas keep arrays of jets sized for their largest case
  // (an XY polynomial's powers, a Zernike sum's), and zeroing them on every evaluation cost
  // more than the arithmetic.
  Jet() = default;
  Jet(double value) : v(value), dx(0), dy(0) {  // NOLINT: constants mix freely with jets
    if constexpr (Order == 2) this->dxx = this->dxy = this->dyy = 0;
  }
  static Jet variable_x(double x) {
    Jet j(x);
    j.dx = 1;
    return j;
  }
  static Jet variable_y(double y) {
    Jet j(y);
    j.dy = 1;
    return j;
  }

  // f(this) given f, f', f'' at the value: the chain rule.
  Jet apply(double f, double f1, double f2) const {
    Jet r(f);
    r.dx = f1 * dx;
    r.dy = f1 * dy;
    if constexpr (Order == 2) {
      r.dxx = f1 * this->dxx + f2 * dx * dx;
      r.dxy = f1 * this->dxy + f2 * dx * dy;
      r.dyy = f1 * this->dyy + f2 * dy * dy;
    }
    return r;
  }

  Jet& operator+=(const Jet& b) {
    v += b.v;
    dx += b.dx;
    dy += b.dy;
    if constexpr (Order == 2) {
      this->dxx += b.dxx;
      this->dxy += b.dxy;
      this->dyy += b.dyy;
    }
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    v -= b.v;
    dx -= b.dx;
    dy -= b.dy;
    if constexpr (Order == 2) {
      this->dxx -= b.dxx;
      this->dxy -= b.dxy;
      this->dyy -= b.dyy;
    }
    return *this;
  }
  Jet& operator*=(double s) {
    v *= s;
    dx *= s;
    dy *= s;
    if constexpr (Order == 2) {
      this->dxx *= s;
      this->dxy *= s;
      this->dyy *= s;
    }
    return *this;
  }
};

template <int N>
Jet<N> operator+(Jet<N> a, const Jet<N>& b) {
  return a += b;
}
template <int N>
Jet<N> operator-(Jet<N> a, const Jet<N>& b) {
  return a -= b;
}
template <int N>
Jet<N> operator+(Jet<N> a, double b) {
  a.v += b;
  return a;
}
template <int N>
Jet<N> operator+(double a, Jet<N> b) {
  b.v += a;
  return b;
}
template <int N>
Jet<N> operator-(Jet<N> a, double b) {
  a.v -= b;
  return a;
}
template <int N>
Jet<N> operator-(double a, const Jet<N>& b) {
  return Jet<N>(a) - b;
}
template <int N>
Jet<N> operator-(Jet<N> a) {
  a *= -1.0;
  return a;
}
template <int N>
Jet<N> operator*(Jet<N> a, double s) {
  return a *= s;
}
template <int N>
Jet<N> operator*(double s, Jet<N> a) {
  return a *= s;
}

template <int N>
Jet<N> operator*(const Jet<N>& a, const Jet<N>& b) {
  Jet<N> r(a.v * b.v);
  r.dx = a.dx * b.v + a.v * b.dx;
  r.dy = a.dy * b.v + a.v * b.dy;
  if constexpr (N == 2) {
    r.dxx = a.dxx * b.v + 2 * a.dx * b.dx + a.v * b.dxx;
    r.dxy = a.dxy * b.v + a.dx * b.dy + a.dy * b.dx + a.v * b.dxy;
    r.dyy = a.dyy * b.v + 2 * a.dy * b.dy + a.v * b.dyy;
  }
  return r;
}

template <int N>
Jet<N> reciprocal(const Jet<N>& a) {
  const double i = 1.0 / a.v;
  return a.apply(i, -i * i, 2 * i * i * i);
}
template <int N>
Jet<N> operator/(const Jet<N>& a, const Jet<N>& b) {
  return a * reciprocal(b);
}
template <int N>
Jet<N> operator/(const Jet<N>& a, double b) {
  return a * (1.0 / b);
}
template <int N>
Jet<N> operator/(double a, const Jet<N>& b) {
  return a * reciprocal(b);
}

template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  const double s = std::sqrt(a.v);
  return a.apply(s, 0.5 / s, -0.25 / (s * a.v));
}
template <int N>
Jet<N> sin(const Jet<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return a.apply(s, c, -s);
}
template <int N>
Jet<N> cos(const Jet<N>& a) {
  const double s = std::sin(a.v), c = std::cos(a.v);
  return a.apply(c, -s, -c);
}

// Plain doubles take the same code path in formulas written for jets.
inline double sqrt(double a) {
  return std::sqrt(a);
}
inline double sin(double a) {
  return std::sin(a);
}
inline double cos(double a) {
  return std::cos(a);
}

}  // namespace freeturn
