#pragma once
// Internal: the collocation matrix N_{k,i} = N_{i,p}(ū_k) of a knot vector at a list of
// parameters, shared by interpolation and least-squares fitting.

#include <Eigen/SparseCore>
#include <vector>

#include "freeturn/nurbs/knot_vector.hpp"

namespace freeturn::nurbs {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// #params × knots.count(), p + 1 non-zeros a row.
SparseMatrix collocation_matrix(const KnotVector& knots, const std::vector<double>& params);

}  // namespace freeturn::nurbs

namespace freeturn::nurbs {

// G_{ij} = ∫ N_i^(k)(u) N_j^(k)(u) du over the domain: the Gram matrix of the k-th
// derivatives (k = 0, 1, 2), exact by (p + 1)-point Gauss–Legendre on each span.
SparseMatrix derivative_gram_matrix(const KnotVector& knots, int k);

}  // namespace freeturn::nurbs
