#pragma once
// Where the tool goes for one contact point: the nose centre, the contact angle, the B
// angle and the programmed point (docs/conventions.md, "Cutter location").

#include <Eigen/Core>
#include <span>
#include <vector>

#include "freeturn/path/contact_point.hpp"

namespace freeturn {

struct CutterLocation {
  ContactPoint contact;
  // ψ: angle of n_p (the normal projected into the radial plane at θ) from +z toward +r.
  double psi = 0;
  Eigen::Vector3d nose_centre = Eigen::Vector3d::Zero();
  double b = 0;  // tool rotation about the machine Y axis (rad), 0 on 3-axis machines
  // The programmed point in the radial plane: radial (signed, mm) and axial (mm)
  // coordinates, and the spindle angle (rad) that brings the contact under the tool
  // (θ, corrected for the tool's centre height).
  double x = 0, z = 0, c = 0;
};

class CutterSink {
 public:
  virtual ~CutterSink() = default;
  virtual void write(std::span<const CutterLocation> chunk) = 0;
};

// Collects everything (tests and small jobs only).
class CutterCollector final : public CutterSink {
 public:
  void write(std::span<const CutterLocation> chunk) override {
    locations.insert(locations.end(), chunk.begin(), chunk.end());
  }
  std::vector<CutterLocation> locations;
};

}  // namespace freeturn
