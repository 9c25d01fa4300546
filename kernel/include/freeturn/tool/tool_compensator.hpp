#pragma once
// The stage between the planner and the machine: contact points in, checked cutter
// locations out, chunk by chunk (the chunk in is the chunk out; nothing else is held).

#include <vector>

#include "freeturn/path/contact_point.hpp"
#include "freeturn/tool/compensation.hpp"
#include "freeturn/tool/tool_checks.hpp"

namespace freeturn {

class ToolCompensator final : public ContactSink {
 public:
  // `design` and `out` must outlive the compensator.
  ToolCompensator(const Surface& design, const CompensationOptions& compensation,
                  const ToolCheckOptions& checks, CutterSink& out)
      : options_(compensation), checker_(design, compensation, checks), out_(out) {}

  // Throws InputError from the first check whose policy is kError.
  void write(std::span<const ContactPoint> chunk) override {
    buffer_.clear();
    for (const ContactPoint& p : chunk) {
      // One sine-cosine pair a point for both, not one in each and a third in the
      // clearance check (at a spiral's angles of thousands of radians: 0.98x the time of
      // an equal-angle compound eye).
      const RadialLine line(p.theta);
      const CutterLocation cl = compensate(p, options_, line);
      checker_.check(cl, line);
      // The edge, |h| off the spindle line, reaches no radius under |h|: compensation
      // leaves X undefined there, and the centre check reports it (an error stops the run).
      // Downgraded, the program is written without those blocks, leaving material about
      // the axis, and the finding marks it UNSAFE.
      if (!edge_reaches(p.point.x() * line.cos + p.point.y() * line.sin,
                        options_.tool.centre_height))
        continue;
      buffer_.push_back(cl);
    }
    out_.write(buffer_);
  }

  const ToolCheckReport& report() const { return checker_.report(); }

 private:
  CompensationOptions options_;
  ToolChecker checker_;
  CutterSink& out_;
  std::vector<CutterLocation> buffer_;  // grows once to the chunk size
};

}  // namespace freeturn
