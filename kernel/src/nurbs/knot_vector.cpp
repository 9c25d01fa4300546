#include "freeturn/nurbs/knot_vector.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "freeturn/core/error.hpp"
#include "freeturn/core/number_text.hpp"

namespace freeturn::nurbs {
namespace {

std::string num(double v) { return shortest_text(v); }

}  // namespace

KnotVector::KnotVector(int degree, std::vector<double> knots)
    : degree_(degree), knots_(std::move(knots)) {
  if (degree_ < 1) throw InputError("degree", "must be at least 1, not " + std::to_string(degree_));
  const std::size_t m = knots_.size();
  const std::size_t p = static_cast<std::size_t>(degree_);
  if (m < 2 * (p + 1))
    throw InputError("knots", "degree " + std::to_string(degree_) + " needs at least " +
                                  std::to_string(2 * (p + 1)) + " knots, got " + std::to_string(m));
  for (std::size_t i = 0; i < m; ++i) {
    if (!std::isfinite(knots_[i]))
      throw InputError("knot " + std::to_string(i), "is not a finite number");
    if (i > 0 && knots_[i] < knots_[i - 1])
      throw InputError("knot " + std::to_string(i),
                       num(knots_[i]) + " is smaller than knot " + std::to_string(i - 1) + " (" +
                           num(knots_[i - 1]) + "): knots must be non-decreasing");
  }
  // Multiplicities: an interior knot repeated p + 1 times would split the curve.
  std::size_t run = 1;
  for (std::size_t i = 1; i <= m; ++i) {
    if (i < m && knots_[i] == knots_[i - 1]) {
      ++run;
      continue;
    }
    const bool at_end = (i - run == 0) || (i == m);
    const std::size_t limit = at_end ? p + 1 : p;
    if (run > limit)
      throw InputError("knot " + std::to_string(i - run),
                       "value " + num(knots_[i - 1]) + " repeats " + std::to_string(run) +
                           " times; at most " + std::to_string(limit) + " allowed for degree " +
                           std::to_string(degree_) + (at_end ? " at an end" : " inside"));
    run = 1;
  }
  if (!(back() > front()))
    throw InputError("knots", "the domain [u_p, u_{m-p}] = [" + num(front()) + ", " + num(back()) +
                                  "] is empty");
}

KnotVector KnotVector::uniform_clamped(int degree, int count) {
  if (count < degree + 1)
    throw InputError("control points",
                     std::to_string(count) + " are too few for degree " + std::to_string(degree));
  std::vector<double> k(static_cast<std::size_t>(count + degree + 1));
  const int interior = count - degree - 1;
  for (int i = 0; i < static_cast<int>(k.size()); ++i) {
    if (i <= degree)
      k[i] = 0.0;
    else if (i >= count)
      k[i] = 1.0;
    else
      k[i] = static_cast<double>(i - degree) / (interior + 1);
  }
  return KnotVector(degree, std::move(k));
}

bool KnotVector::is_clamped() const {
  const std::size_t p = static_cast<std::size_t>(degree_);
  const std::size_t m = knots_.size() - 1;
  return knots_[0] == knots_[p] && knots_[m] == knots_[m - p];
}

int KnotVector::find_span(double u) const {
  // A2.1, with the last span chosen for u = u_{n+1} so that the end point is included.
  const int n = count() - 1;
  if (u >= knots_[n + 1]) {
    int i = n;
    while (i > degree_ && knots_[i] == knots_[i + 1]) --i;
    return i;
  }
  if (u <= knots_[degree_]) {
    int i = degree_;
    while (i < n && knots_[i + 1] <= u) ++i;
    return i;
  }
  // Invariant: knots[low] <= u < knots[high].
  auto first = knots_.begin() + degree_;
  auto last = knots_.begin() + n + 1;
  return static_cast<int>(std::upper_bound(first, last, u) - knots_.begin()) - 1;
}

int KnotVector::find_span(double u, int hint) const {
  const int n = count() - 1;
  if (hint >= degree_ && hint <= n) {
    const auto in = [&](int i) {
      return i >= degree_ && i <= n && knots_[i] <= u && u < knots_[i + 1];
    };
    if (in(hint)) return hint;
    if (in(hint + 1)) return hint + 1;
    if (in(hint - 1)) return hint - 1;
  }
  return find_span(u);
}

int KnotVector::multiplicity(double u) const {
  return static_cast<int>(std::count(knots_.begin(), knots_.end(), u));
}

std::vector<double> KnotVector::breakpoints() const {
  std::vector<double> b;
  for (int i = degree_; i <= count(); ++i) {
    const double k = knots_[i];
    if (b.empty() || k > b.back()) b.push_back(k);
  }
  return b;
}

}  // namespace freeturn::nurbs
