#pragma once
// A surface whose sag is one formula, written once as a template
//   template <typename T> T sag(const T& x, const T& y) const;
// and differentiated exactly by Jet (jet.hpp) for the gradient and the Hessian.

#include "freeturn/surface/jet.hpp"
#include "freeturn/surface/surface.hpp"

namespace freeturn {

template <typename Derived>
class JetSurface : public Surface {
 public:
  void sag_gradient(double x, double y, double& z, double& zx, double& zy) const override {
    const Jet<1> j = self().sag(Jet<1>::variable_x(x), Jet<1>::variable_y(y));
    z = j.v;
    zx = j.dx;
    zy = j.dy;
  }

  HeightDerivatives height_derivatives(double x, double y) const override {
    const Jet<2> j = self().sag(Jet<2>::variable_x(x), Jet<2>::variable_y(y));
    return {j.v, j.dx, j.dy, j.dxx, j.dxy, j.dyy};
  }

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
};

}  // namespace freeturn
