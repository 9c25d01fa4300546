#include "freeturn/pipeline/contact_tape.hpp"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace freeturn {
namespace {

// A point as 15 doubles (the flags as one), so that every value comes back bit for bit.
constexpr std::size_t kFields = 15;

void pack(const ContactPoint& p, double* d) {
  d[0] = p.theta;
  d[1] = p.r;
  for (int i = 0; i < 3; ++i) d[2 + i] = p.point[i], d[5 + i] = p.normal[i];
  d[8] = p.chord_error;
  d[9] = (p.chord_below ? 1.0 : 0.0) + (p.chord_jump ? 2.0 : 0.0);
  d[10] = p.uncut_residual;
  d[11] = p.stand_off;
  d[12] = p.pass_spacing;
  d[13] = p.section_curvature;
  d[14] = p.scallop;
}

void unpack(const double* d, ContactPoint& p) {
  p.theta = d[0];
  p.r = d[1];
  for (int i = 0; i < 3; ++i) p.point[i] = d[2 + i], p.normal[i] = d[5 + i];
  p.chord_error = d[8];
  const int flags = static_cast<int>(d[9]);
  p.chord_below = (flags & 1) != 0;
  p.chord_jump = (flags & 2) != 0;
  p.uncut_residual = d[10];
  p.stand_off = d[11];
  p.pass_spacing = d[12];
  p.section_curvature = d[13];
  p.scallop = d[14];
}

}  // namespace

ContactTape::ContactTape(std::size_t max_bytes) : max_bytes_(max_bytes) {}

void ContactTape::record(std::span<const ContactPoint> chunk) {
  if (!complete_) return;
  const std::uint64_t count = chunk.size();
  const std::size_t bytes = sizeof count + count * kFields * sizeof(double);
  if (bytes_ + bytes > max_bytes_) {
    complete_ = false;
    file_.reset();
    return;
  }
  if (!file_) file_.reset(std::tmpfile());
  std::vector<double> packed(count * kFields);  // one chunk, not one per point
  for (std::size_t i = 0; i < chunk.size(); ++i) pack(chunk[i], &packed[i * kFields]);
  if (!file_ || std::fwrite(&count, sizeof count, 1, file_.get()) != 1 ||
      (count > 0 &&
       std::fwrite(packed.data(), sizeof(double), packed.size(), file_.get()) != packed.size())) {
    complete_ = false;
    file_.reset();
    return;
  }
  bytes_ += bytes;
}

void ContactTape::replay(ContactSink& sink) const {
  if (!complete_ || !file_) return;
  std::FILE* f = file_.get();
  if (std::fflush(f) != 0 || std::fseek(f, 0, SEEK_SET) != 0)
    throw std::runtime_error("the recorded path cannot be read back");
  std::vector<double> packed;
  std::vector<ContactPoint> chunk;
  std::size_t read = 0;
  while (read < bytes_) {
    std::uint64_t count = 0;
    if (std::fread(&count, sizeof count, 1, f) != 1)
      throw std::runtime_error("the recorded path cannot be read back");
    packed.resize(count * kFields);
    chunk.resize(count);
    if (count > 0 && std::fread(packed.data(), sizeof(double), packed.size(), f) != packed.size())
      throw std::runtime_error("the recorded path cannot be read back");
    for (std::size_t i = 0; i < count; ++i) unpack(&packed[i * kFields], chunk[i]);
    sink.write(chunk);
    read += sizeof count + count * kFields * sizeof(double);
  }
}

}  // namespace freeturn
