#pragma once
// How a PVT controller moves between blocks (position-velocity-time: the Precitech UPx in
// PVT mode that paper 001 cut with). The program carries positions only, and a time per
// block (or one for all): the controller derives each axis's velocity at a block from the
// blocks on either side, the central difference over their times,
//
//   v_k = (q_{k+1} − q_{k−1}) / (t_{k+1} − t_{k−1}),
//
// one-sided at the program's ends (pass the end block itself as its missing neighbour),
// and moves each axis along the cubic Hermite through the two positions and velocities.
// This is the one statement of that rule: the planner measures every segment's chord
// error on this motion (path_stepper.hpp) and the simulator cuts along it
// (cut_simulation.cpp). A block's time is what the program implies: Δθ / ω on a spiral at
// constant spindle speed, the X-Z chord over the feed in profile mode; only ratios of
// times shape the cubic, so either may be given in any unit.

namespace freeturn::pvt {

// The velocity at a block whose neighbours lie at q_before and q_after, dt apart in time.
// Zero when they coincide in time (a held nose: the axes do not move).
inline double velocity(double q_before, double q_after, double dt) {
  return dt > 0 ? (q_after - q_before) / dt : 0.0;
}

// The position a fraction u ∈ [0, 1] of the way through a block of time h that runs from
// qa (velocity va) to qb (velocity vb).
inline double hermite(double qa, double va, double qb, double vb, double h, double u) {
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * qa + (u3 - 2 * u2 + u) * h * va + (-2 * u3 + 3 * u2) * qb +
         (u3 - u2) * h * vb;
}

// The velocity dq/ds of largest size along that block's cubic, with its sign. The
// velocity is quadratic in the fraction u: its extremes lie at the ends or at its vertex
// inside the block.
inline double extreme_velocity(double qa, double va, double qb, double vb, double h) {
  const double slope = (qb - qa) / h;
  // v(u) = a u² + b u + va.
  const double a = 3 * (va + vb) - 6 * slope, b = 6 * slope - 4 * va - 2 * vb;
  const auto size = [](double v) { return v < 0 ? -v : v; };
  double extreme = size(vb) > size(va) ? vb : va;
  if (a != 0) {
    const double u = -b / (2 * a);
    if (u > 0 && u < 1) {
      const double v = va - b * b / (4 * a);
      if (size(v) > size(extreme)) extreme = v;
    }
  }
  return extreme;
}

// The largest speed |dq/ds| along that block's cubic.
inline double peak_speed(double qa, double va, double qb, double vb, double h) {
  const double v = extreme_velocity(qa, va, qb, vb, h);
  return v < 0 ? -v : v;
}

// The accelerations d²q/ds² at that block's start and end. The acceleration is linear in
// u, so the larger of their sizes is the block's largest.
inline void end_accelerations(double qa, double va, double qb, double vb, double h,
                              double& at_start, double& at_end) {
  const double slope = (qb - qa) / h;
  at_start = (6 * slope - 4 * va - 2 * vb) / h;
  at_end = (-6 * slope + 2 * va + 4 * vb) / h;
}

}  // namespace freeturn::pvt
