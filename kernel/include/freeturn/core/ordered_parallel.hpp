#pragma once
// Work items made on several threads and used in order on the calling one: the shape of a
// streaming pipeline whose first stage is the costly one (planning a spiral band by band)
// and whose later stages must see the items in sequence (compensation, axes, the post).
//
// produce(i, slot) fills a slot for item i on a worker thread; consume(i, slot) reads it on
// the calling thread, items in index order. At most `window` items are made ahead of the
// consumer, so memory stays bounded by the window whatever the count, and slots are
// reused (a producer that clears and refills a vector allocates nothing once warm). The
// items' contents must not depend on which thread made them: then the output is the same
// on any number of threads.
//
// An exception thrown by produce(i) is rethrown from consume's turn for item i, so the
// caller sees the first failure in order, as a sequential loop would. An exception from
// consume stops the workers before it propagates. threads ≤ 1 runs inline, no thread.

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace freeturn {

template <class Slot, class Produce, class Consume>
void ordered_parallel(int threads, long count, int window, Produce&& produce, Consume&& consume) {
  if (count <= 0) return;
  if (threads <= 1) {
    Slot slot;
    for (long i = 0; i < count; ++i) {
      produce(i, slot);
      consume(i, slot);
    }
    return;
  }
  window = std::max(window, threads);
  struct Entry {
    Slot slot;
    long item = -1;  // the item it holds, once made
    std::exception_ptr error;
  };
  std::vector<Entry> slots(static_cast<std::size_t>(window));
  std::mutex mutex;
  std::condition_variable changed;
  long next_item = 0;  // the next item a worker takes
  long consumed = 0;   // items consumed so far
  bool stop = false;

  const auto work = [&] {
    for (;;) {
      long i;
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return stop || next_item >= count || next_item < consumed + window; });
        if (stop || next_item >= count) return;
        i = next_item++;
      }
      Entry& e = slots[static_cast<std::size_t>(i % window)];
      std::exception_ptr error;
      try {
        produce(i, e.slot);
      } catch (...) {
        error = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        e.error = error;
        e.item = i;
      }
      changed.notify_all();
    }
  };
  std::vector<std::thread> workers;
  const auto finish = [&] {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    changed.notify_all();
    for (std::thread& t : workers) t.join();
    workers.clear();
  };
  try {
    for (int t = 0; t < threads; ++t) workers.emplace_back(work);
    for (long i = 0; i < count; ++i) {
      Entry& e = slots[static_cast<std::size_t>(i % window)];
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return e.item == i; });
      }
      if (e.error) std::rethrow_exception(e.error);
      consume(i, e.slot);
      {
        const std::lock_guard<std::mutex> lock(mutex);
        ++consumed;
      }
      changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
}

}  // namespace freeturn
