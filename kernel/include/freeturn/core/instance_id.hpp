#pragma once
// A number no other object of this process has had: fresh on construction, on copy and
// on assignment. A thread's cache of what an immutable object derives (a NURBS height
// field's span, a lenslet array's crease candidates) is keyed by it, not by the object's
// address, which a later object could reuse.

#include <cstdint>

namespace freeturn {

struct InstanceId {
  std::uint64_t value;
  InstanceId();
  InstanceId(const InstanceId&) : InstanceId() {}
  InstanceId& operator=(const InstanceId&);
};

}  // namespace freeturn
