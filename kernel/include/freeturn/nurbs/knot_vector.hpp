#pragma once
// A validated knot vector U = {u_0, …, u_m} for B-splines of degree p with n + 1 = m − p
// basis functions (Piegl & Tiller, The NURBS Book, 2nd ed., §2.2).

#include <span>
#include <vector>

namespace freeturn::nurbs {

class KnotVector {
 public:
  KnotVector() = default;

  // Validates and stores `knots` for `degree` (p ≥ 1). Throws InputError naming the
  // offending knot when: fewer than 2(p + 1) knots; a knot is not finite; the knots
  // decrease; an interior knot repeats more than p times or an end knot more than
  // p + 1 times; the domain [u_p, u_{m−p}] is empty.
  KnotVector(int degree, std::vector<double> knots);

  // Uniform clamped knots on [0, 1] for `count` basis functions of `degree`.
  static KnotVector uniform_clamped(int degree, int count);

  int degree() const { return degree_; }
  // Number of basis functions (= control points) n + 1 = m − p.
  int count() const { return static_cast<int>(knots_.size()) - degree_ - 1; }
  std::span<const double> knots() const { return knots_; }
  double operator[](int i) const { return knots_[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(knots_.size()); }

  // The parameter domain [u_p, u_{m−p}].
  double front() const { return knots_[static_cast<std::size_t>(degree_)]; }
  double back() const { return knots_[knots_.size() - 1 - static_cast<std::size_t>(degree_)]; }

  // True when the first and last p + 1 knots are equal (the curve interpolates its end
  // control points).
  bool is_clamped() const;

  // Knot span index i with u_i ≤ u < u_{i+1}, p ≤ i ≤ n; u is clamped to the domain and
  // u = back() maps to the last non-empty span. Binary search (A2.1).
  int find_span(double u) const;
  // The same, first trying `hint` and its neighbours: O(1) when the parameter moves
  // little between calls, as it does along a path.
  int find_span(double u, int hint) const;

  // The Greville abscissa of control point i, (u_{i+1} + … + u_{i+p}) / p: placed at these,
  // control points of a linear function make the spline reproduce it (§9.3).
  double greville(int i) const {
    double sum = 0;
    for (int j = 1; j <= degree_; ++j) sum += knots_[static_cast<std::size_t>(i + j)];
    return sum / degree_;
  }

  // Multiplicity of the knot value u (0 when u is not a knot).
  int multiplicity(double u) const;

  // The distinct knot values inside the domain, front() and back() included.
  std::vector<double> breakpoints() const;

 private:
  int degree_ = 0;
  std::vector<double> knots_;
};

}  // namespace freeturn::nurbs
