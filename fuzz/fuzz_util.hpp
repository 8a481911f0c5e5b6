// Shared helpers of the libFuzzer targets.
//
// The Triangle readers take a path, so each input is written to a file in a
// private temporary directory (on /dev/shm when it is there: no disk I/O)
// and read back. The directory is removed at exit.
#pragma once
#include <fcntl.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>
#include <typeinfo>
#include <vector>

#include "deltamesh/errors.hpp"

namespace deltamesh::fuzz {

// Aborts (a crash libFuzzer records) with a message on stderr.
[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "\n==deltamesh-fuzz== invariant violated: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

#define DELTAMESH_FUZZ_CHECK(cond, msg)                                                   \
  do {                                                                                    \
    if (!(cond)) ::deltamesh::fuzz::fail(std::string(#cond " -- ") + std::string(msg)); \
  } while (0)

class TempDir {
 public:
  TempDir() {
    const char* base = ::access("/dev/shm", W_OK) == 0 ? "/dev/shm" : (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
    std::string tmpl = std::string(base) + "/deltamesh-fuzz-XXXXXX";
    if (::mkdtemp(tmpl.data()) == nullptr) fail("cannot create a temporary directory in " + std::string(base));
    dir_ = tmpl;
  }
  ~TempDir() {
    for (const std::string& f : files_) ::unlink(f.c_str());
    ::rmdir(dir_.c_str());
  }
  // Writes `data` to `name` in the directory (replacing it); returns the path.
  std::string write(const std::string& name, std::string_view data) {
    const std::string path = dir_ + "/" + name;
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) fail("cannot write " + path);
    std::size_t done = 0;
    while (done < data.size()) {
      const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
      if (n <= 0) fail("cannot write " + path);
      done += static_cast<std::size_t>(n);
    }
    ::close(fd);
    remember(path);
    return path;
  }
  void remove(const std::string& name) { ::unlink((dir_ + "/" + name).c_str()); }
  const std::string& dir() const { return dir_; }

 private:
  void remember(const std::string& path) {
    for (const std::string& f : files_)
      if (f == path) return;
    files_.push_back(path);
  }
  std::string dir_;
  std::vector<std::string> files_;
};

// One directory per process, removed by the static destructor at exit.
inline TempDir& temp_dir() {
  static TempDir dir;
  return dir;
}

// The number of lines of `text` as the readers count them (a last line
// without a final newline counts), at least 1.
inline std::size_t line_count(std::string_view text) {
  std::size_t n = 0;
  for (const char c : text) n += c == '\n';
  if (!text.empty() && text.back() != '\n') ++n;
  return n == 0 ? 1 : n;
}

// A ParseError must name the file it was given and a line of it.
inline void check_parse_error(const ParseError& e, const std::string& path, std::string_view text) {
  DELTAMESH_FUZZ_CHECK(e.file() == path, std::string("ParseError names '") + e.file() + "': " + e.what());
  DELTAMESH_FUZZ_CHECK(e.line() >= 1 && e.line() <= line_count(text),
                       "ParseError line " + std::to_string(e.line()) + " outside the file (" +
                           std::to_string(line_count(text)) + " lines): " + e.what());
  DELTAMESH_FUZZ_CHECK(!e.problem().empty(), "ParseError without a problem");
}

// Called in a catch (...) after the bad-input errors a target expects were
// caught: whatever is left is a bug. InternalError (a broken invariant) is a
// bug by its type, as is any exception that is not one of the library's
// typed errors.
[[noreturn]] inline void unexpected_exception(const char* where) {
  try {
    throw;
  } catch (const InternalError& e) {
    fail(std::string(where) + ": internal error (a bug) in " + e.where() + ": " + e.what());
  } catch (const std::exception& e) {
    fail(std::string(where) + ": unexpected exception " + typeid(e).name() + ": " + e.what());
  } catch (...) {
    fail(std::string(where) + ": unexpected non-standard exception");
  }
}

}  // namespace deltamesh::fuzz
