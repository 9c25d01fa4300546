#pragma once
// Calls into a post-processor plugin under watch. A plugin runs in freeturn's process, so
// a crash there cannot be unwound from, and a hang would hold the run forever. During a
// call, a crash signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) or the call outliving
// its time limit removes every temporary output file (AtomicFile) and hands a message
// naming the plugin and the call to the plugin fault handler, which must end the process:
// no output of the run stays behind; files that were there before are untouched.
//
// The handler is the embedder's: a service may log elsewhere, or abort() for a core
// file; the command line keeps the default. It runs in a signal handler or on the watchdog thread, so it may only use
// async-signal-safe calls (write(2), _exit, abort), and it must not return. Without one,
// the library writes the message to stderr and _exits with kExitPluginFault.

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace freeturn {

inline constexpr int kExitPluginFault = 3;

using PluginFaultHandler = void (*)(const char* message);
// Sets the process-wide handler (nullptr: the default above). Not thread-safe with a
// plugin call in progress: set it once, before the first run.
void set_plugin_fault_handler(PluginFaultHandler handler);

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
