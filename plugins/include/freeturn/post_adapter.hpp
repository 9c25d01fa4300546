#pragma once
// Writing a post-processor as a C++ class (header only). The adapter supplies the C
// function table of post_plugin.h: it constructs the class, forwards each call, and turns
// every exception into the error message the ABI returns, so nothing C++ crosses the
// boundary.
//
//   class MyPost {
//    public:
//     MyPost(const ft_program_info& info, Output& out, FlatSettings& settings);
//     void begin();
//     void blocks(const ft_block* blocks, std::size_t count);
//     void end();
//   };
//   FREETURN_EXPORT_POST(MyPost, "mine")
//
// Throw PostError (or any std::exception) with a message to refuse. Settings the class
// never reads are refused after construction, listing the ones it knows.

#include <cstdio>
#include <stdexcept>
#include <string>

#include "freeturn/post_plugin.h"
#include "freeturn/post_settings.hpp"

namespace freeturn::post {

struct PostError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The host's writer, with C++ conveniences.
class Output {
 public:
  explicit Output(const ft_writer& w) : w_(w) {}
  void put(const std::string& s) const {
    if (w_.write(w_.context, s.data(), s.size()) != 0) throw PostError("cannot write the program");
  }
  void open_file(const std::string& name) const {
    if (w_.open_file(w_.context, name.c_str()) != 0) throw PostError("cannot open " + name);
  }
  void select_main() const {
    if (w_.select_main(w_.context) != 0) throw PostError("cannot return to the main program");
  }

 private:
  const ft_writer& w_;
};

template <class Post>
struct Adapter {
  struct Instance {
    Instance(const ft_program_info& info, const ft_writer& writer, FlatSettings& settings)
        : out(writer), post(info, out, settings) {}
    Output out;  // before `post`, which keeps a reference to it
    Post post;
  };

  static int fail(char* error, std::size_t size, const char* what) {
    std::snprintf(error, size, "%s", what);
    return 1;
  }

  static void* create(const ft_program_info* info, const ft_writer* writer, char* error,
                      std::size_t size) {
    try {
      FlatSettings settings;
      std::string message;
      if (!settings.parse(info->dialect_settings, message)) throw PostError(message);
      auto* instance = new Instance(*info, *writer, settings);
      if (const std::string key = settings.unknown_key(); !key.empty()) {
        delete instance;
        throw PostError("unknown setting '" + key + "' (known: " + settings.known_keys() + ")");
      }
      return instance;
    } catch (const std::exception& e) {
      fail(error, size, e.what());
      return nullptr;
    }
  }
  static int begin(void* h, char* error, std::size_t size) {
    try {
      static_cast<Instance*>(h)->post.begin();
      return 0;
    } catch (const std::exception& e) {
      return fail(error, size, e.what());
    }
  }
  static int blocks(void* h, const ft_block* b, std::size_t n, char* error, std::size_t size) {
    try {
      static_cast<Instance*>(h)->post.blocks(b, n);
      return 0;
    } catch (const std::exception& e) {
      return fail(error, size, e.what());
    }
  }
  static int end(void* h, char* error, std::size_t size) {
    try {
      static_cast<Instance*>(h)->post.end();
      return 0;
    } catch (const std::exception& e) {
      return fail(error, size, e.what());
    }
  }
  static void destroy(void* h) { delete static_cast<Instance*>(h); }
};

}  // namespace freeturn::post

#define FREETURN_EXPORT_POST(PostClass, name_string)                                             \
  extern "C" __attribute__((visibility("default"))) const ft_post* freeturn_post_entry(void) { \
    using A = ::freeturn::post::Adapter<PostClass>;                                              \
    static const ft_post table = {FREETURN_POST_ABI_VERSION, name_string, A::create, A::begin,  \
                                  A::blocks, A::end, A::destroy};                                \
    return &table;                                                                               \
  }
