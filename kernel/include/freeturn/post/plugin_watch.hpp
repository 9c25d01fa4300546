#pragma once
// Calls into a post-processor plugin under watch. A plugin runs in freeturn's process, so
// a crash there cannot be unwound from, and a hang would hold the run forever. During a
// call, a crash signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) or the call outliving
// its time limit ends the process: a message naming the plugin and the call goes to
// stderr, every temporary output file is removed (AtomicFile), and the exit code is
// kExitPluginFault. No output of the run stays behind; files that were there before are
// untouched.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace freeturn {

inline constexpr int kExitPluginFault = 3;

class PluginWatch {
 public:
  // The time limit of each call, in seconds: FREETURN_PLUGIN_TIMEOUT, or 60.
  explicit PluginWatch(std::string plugin_name);
  ~PluginWatch();
  PluginWatch(const PluginWatch&) = delete;
  PluginWatch& operator=(const PluginWatch&) = delete;

  // Brackets one call; `call` names it in messages ("blocks", "end").
  class Call {
   public:
    Call(PluginWatch& watch, const char* call);
    ~Call();
    Call(const Call&) = delete;
    Call& operator=(const Call&) = delete;

   private:
    PluginWatch& watch_;
  };

  double limit_seconds() const { return limit_; }

 private:
  void watchdog();

  std::string name_;
  double limit_ = 60;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false, in_call_ = false;
  const char* call_ = "";
  std::chrono::steady_clock::time_point deadline_;
  std::thread thread_;
};

}  // namespace freeturn
