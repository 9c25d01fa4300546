#include "freeturn/core/instance_id.hpp"

#include <atomic>

namespace freeturn {
namespace {

std::atomic<std::uint64_t> next_instance_id{1};

std::uint64_t fresh_id() { return next_instance_id.fetch_add(1, std::memory_order_relaxed); }

}  // namespace

InstanceId::InstanceId() : value(fresh_id()) {}

InstanceId& InstanceId::operator=(const InstanceId&) {
  value = fresh_id();
  return *this;
}

}  // namespace freeturn
