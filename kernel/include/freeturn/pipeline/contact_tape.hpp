#pragma once
// The planner's output for one pass, kept in a temporary file so that it can be sent again
// without planning again (run_pipeline.cpp: a constant-rpm spiral is planned once to find
// its speed, then written at that speed; the plan does not depend on the speed).
//
// The tape replays the exact chunks it was given, in order, bit for bit: what a sink makes
// of a chunk may depend on where chunks begin, so a replay matches the planner's own calls.
// It holds at most `max_bytes`; a path longer than that, or a file that cannot be written
// (no temporary folder, a full disk), leaves the tape incomplete, and the caller plans
// again. Memory stays one chunk whatever the path's length.

#include <cstddef>
#include <cstdio>
#include <memory>
#include <span>

#include "freeturn/path/contact_point.hpp"

namespace freeturn {

class ContactTape {
 public:
  explicit ContactTape(std::size_t max_bytes);

  // Appends one chunk (a ContactSink's write), unless the tape is already incomplete.
  void record(std::span<const ContactPoint> chunk);
  // Every chunk recorded so far was kept.
  bool complete() const { return complete_; }
  // Sends the recorded chunks to `sink`, as they were recorded. Throws std::runtime_error
  // when the file cannot be read back (a tape that is not complete replays nothing).
  void replay(ContactSink& sink) const;

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Closer> file_;  // deleted by the system when closed
  std::size_t max_bytes_, bytes_ = 0;
  bool complete_ = true;
};

// A sink that records what it passes on (the probe's tee).
class RecordingSink final : public ContactSink {
 public:
  RecordingSink(ContactSink& next, ContactTape& tape) : next_(next), tape_(tape) {}
  void write(std::span<const ContactPoint> chunk) override {
    tape_.record(chunk);
    next_.write(chunk);
  }

 private:
  ContactSink& next_;
  ContactTape& tape_;
};

}  // namespace freeturn
