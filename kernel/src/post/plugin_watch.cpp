#include "freeturn/post/plugin_watch.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "freeturn/io/atomic_file.hpp"

namespace freeturn {
namespace {

constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT};
constexpr int kSignalCount = sizeof kSignals / sizeof kSignals[0];

// What the handler writes, prepared before the call (a handler may only write(2)).
char g_crash_message[768];
struct sigaction g_previous[kSignalCount];
// An alternate stack, so a plugin that overflows its stack is still reported.
alignas(16) char g_signal_stack[1 << 16];

void write_all(const char* text) {
  std::size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<std::size_t>(n);
  }
}

void default_fault_handler(const char* message) {
  write_all(message);
  ::_exit(kExitPluginFault);
}

std::atomic<PluginFaultHandler> g_fault_handler{nullptr};

// Removes the run's temporaries and hands the message to the handler, which ends the
// process (the default's _exit if it returns).
[[noreturn]] void end_with(const char* message) {
  AtomicFile::remove_all_temporaries();
  const PluginFaultHandler handler = g_fault_handler.load();
  (handler ? handler : default_fault_handler)(message);
  ::_exit(kExitPluginFault);
}

// Appends `text` to the message in `out` (capacity `size`): strlen and memcpy only, safe
// in a signal handler.
void append(char* out, std::size_t size, const char* text) {
  const std::size_t used = std::strlen(out), room = size - 1 - used, n = std::strlen(text);
  std::memcpy(out + used, text, n < room ? n : room);
  out[used + (n < room ? n : room)] = '\0';
}

extern "C" void on_crash(int signal) {
  const char* name = signal == SIGSEGV   ? "SIGSEGV"
                     : signal == SIGBUS  ? "SIGBUS"
                     : signal == SIGILL  ? "SIGILL"
                     : signal == SIGFPE  ? "SIGFPE"
                                         : "SIGABRT";
  append(g_crash_message, sizeof g_crash_message, name);
  append(g_crash_message, sizeof g_crash_message, "); no NC file was written\n");
  end_with(g_crash_message);
}

}  // namespace

void set_plugin_fault_handler(PluginFaultHandler handler) { g_fault_handler.store(handler); }

PluginWatch::PluginWatch(std::string plugin_name) : name_(std::move(plugin_name)) {
  if (const char* v = std::getenv("FREETURN_PLUGIN_TIMEOUT")) {
    char* end = nullptr;
    const double seconds = std::strtod(v, &end);
    if (end != v && seconds > 0) limit_ = seconds;
  }
  static bool stack_set = false;
  if (!stack_set) {
    stack_t stack{};
    stack.ss_sp = g_signal_stack;
    stack.ss_size = sizeof g_signal_stack;
    ::sigaltstack(&stack, nullptr);
    stack_set = true;
  }
  thread_ = std::thread([this] { watchdog(); });
}

PluginWatch::~PluginWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void PluginWatch::watchdog() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (!in_call_) {
      wake_.wait(lock);
      continue;
    }
    if (wake_.wait_until(lock, deadline_) == std::cv_status::timeout && in_call_ && !stop_ &&
        std::chrono::steady_clock::now() >= deadline_) {
      char message[768];
      std::snprintf(message, sizeof message,
                    "freeturn: post-processor '%s' did not return from %s within %g s "
                    "(FREETURN_PLUGIN_TIMEOUT); no NC file was written\n",
                    name_.c_str(), call_, limit_);
      end_with(message);
    }
  }
}

PluginWatch::Call::Call(PluginWatch& watch, const char* call) : watch_(watch) {
  std::snprintf(g_crash_message, sizeof g_crash_message,
                "freeturn: post-processor '%s' crashed in %s (", watch.name_.c_str(), call);
  struct sigaction action{};
  action.sa_handler = on_crash;
  action.sa_flags = SA_ONSTACK | SA_RESETHAND;
  sigemptyset(&action.sa_mask);
  for (int k = 0; k < kSignalCount; ++k) ::sigaction(kSignals[k], &action, &g_previous[k]);
  {
    std::lock_guard<std::mutex> lock(watch.mutex_);
    watch.in_call_ = true;
    watch.call_ = call;
    watch.deadline_ = std::chrono::steady_clock::now() +
                      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                          std::chrono::duration<double>(watch.limit_));
  }
  watch.wake_.notify_all();
}

PluginWatch::Call::~Call() {
  {
    std::lock_guard<std::mutex> lock(watch_.mutex_);
    watch_.in_call_ = false;
  }
  for (int k = 0; k < kSignalCount; ++k) ::sigaction(kSignals[k], &g_previous[k], nullptr);
}

}  // namespace freeturn
