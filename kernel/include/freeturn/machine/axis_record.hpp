#pragma once
// Machine axis values for one block, in machine units (mm, degrees) after the machine's
// signs, offsets and C wrapping, with the block's duration.

#include <span>
#include <vector>

namespace freeturn {

struct AxisRecord {
  double x = 0, z = 0, c = 0, b = 0;  // mm, mm, °, °
  double time = 0;  // s: the block's duration (0 for the first)
};

class AxisSink {
 public:
  virtual ~AxisSink() = default;
  virtual void write(std::span<const AxisRecord> chunk) = 0;
};

class AxisCollector final : public AxisSink {
 public:
  void write(std::span<const AxisRecord> chunk) override {
    records.insert(records.end(), chunk.begin(), chunk.end());
  }
  std::vector<AxisRecord> records;
};

}  // namespace freeturn
