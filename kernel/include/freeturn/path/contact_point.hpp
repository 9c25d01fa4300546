#pragma once
// The planner's output record and the stream that carries it (docs/path.md).
//
// A path is never held whole: planners fill a fixed-size chunk of ContactPoints and hand
// it to a ContactSink, so a 50-million-point pass runs in the memory of one chunk.

#include <Eigen/Core>
#include <algorithm>
#include <span>
#include <vector>

namespace freeturn {

// One cutter contact point, in the workpiece frame (docs/conventions.md).
struct ContactPoint {
  double theta = 0;  // spindle angle (rad), unwrapped, non-decreasing along the path
  double r = 0;      // radial position of the contact, ≥ 0 (mm)
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // on the design surface: (r cos θ, r sin θ, z)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, toward the tool
  // Predicted chord error of the segment that ends here (mm), the band's figure: the
  // stand-off plus the largest deviation of the machine's interpolated motion from the
  // blocks' stand-off, either way, along the normal of the radial section (on a surface
  // that slopes across the section, a few per cent from the figure along its own normal);
  // 0 for the first point. Where that deviation leans away from the design this is the
  // motion's largest distance from it; where it dips toward the design (a PVT path's first
  // and last cubics, whose end velocities are one-sided), the motion there comes
  // 2·stand_off − chord_error above the design, and its largest distance may be as little
  // as the stand-off.
  double chord_error = 0;
  // Which side of the design that worst deviation lies: below it (the motion cuts into
  // the design) or above (it leaves material, which adds to the scallop).
  bool chord_below = false;
  // The segment crosses a jump of the nose centre (a crease sharper than the nose,
  // docs/path.md): the motion swings across the crease and errs on both sides by up to
  // chord_error.
  bool chord_jump = false;
  // Where the nose is held at a concave crease sharper than itself (path/section_envelope.hpp):
  // the depth of material it leaves above the crease (mm, vertical), 0 elsewhere. `point`
  // is then the nose's touch on this flank, not the spiral's own contact.
  double uncut_residual = 0;
  // How far the programmed tool stands off the design along the section normal here (mm):
  // half the chord tolerance under the chord rule (cutter_points.hpp, stand_off_for), so
  // that the interpolated motion never dips below the design. Compensation adds it to R.
  double stand_off = 0;
  // How deep the motion of the segment that ends here cuts into the design (mm; 0 where it
  // stays above): chord_error counts from the band's centre, stand_off above the design.
  double dip_below_design() const { return dip_below(0.0); }
  // How far the motion comes below a floor `floor` above the design (mm; 0 where it stays
  // above). chord_below marks the segments that come below the planner's floor (the real
  // edge's reach past the round nose, cutter_points.hpp), so a floor up to that one is
  // judged in full.
  double dip_below(double floor) const {
    return chord_below ? std::max(0.0, chord_error - 2 * stand_off + floor) : 0.0;
  }
  // Pass spacing across adjacent turns along the surface (mm), the curvature of the
  // surface's radial section (1/mm, > 0 concave as seen from the tool), and the scallop
  // height they leave with the tool's nose radius (mm; 0 when no nose radius was given).
  double pass_spacing = 0;
  double section_curvature = 0;
  double scallop = 0;
};

class ContactSink {
 public:
  virtual ~ContactSink() = default;
  // Called with consecutive chunks of the path, in order.
  virtual void write(std::span<const ContactPoint> chunk) = 0;
};

// Collects everything (tests and small jobs only: memory grows with the path).
class ContactCollector final : public ContactSink {
 public:
  void write(std::span<const ContactPoint> chunk) override {
    points.insert(points.end(), chunk.begin(), chunk.end());
  }
  std::vector<ContactPoint> points;
};

// Buffers points into fixed chunks for a sink. flush() sends the rest; the destructor
// does not (a planner that throws must not deliver half a chunk).
class ContactChunker {
 public:
  static constexpr std::size_t kChunkSize = 4096;
  explicit ContactChunker(ContactSink& sink) : sink_(sink) { buffer_.reserve(kChunkSize); }
  void push(const ContactPoint& p) {
    buffer_.push_back(p);
    if (buffer_.size() == kChunkSize) flush();
  }
  void flush() {
    if (!buffer_.empty()) sink_.write(buffer_);
    buffer_.clear();
  }

 private:
  ContactSink& sink_;
  std::vector<ContactPoint> buffer_;
};

}  // namespace freeturn
