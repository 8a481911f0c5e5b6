// Output files that appear whole or not at all.
//
// AtomicFile writes to `<path>.tmp.<pid>.<k>` in the same directory (the
// first k whose file does not exist yet, created exclusively, so concurrent
// writers of one path never share a temporary) and renames it onto `path` on
// commit(); the last rename wins, and the file is always one writer's whole. An AtomicFile destroyed without commit() (an
// exception on the way) removes its temporary file, so a failed write never
// leaves a partial output file behind. Errors throw IoError naming the path
// and the system's reason.
#pragma once
#include <string>
#include <string_view>

namespace deltamesh::io {

class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  // Appends data (the whole of it, or throws).
  void write(std::string_view data);
  // Closes the temporary file and renames it onto the target path.
  void commit();

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_; }

 private:
  static constexpr int kMaxTempAttempts = 1000;
  [[noreturn]] void fail(const std::string& doing, int err);
  void discard() noexcept;

  std::string path_;
  std::string temp_;
  int fd_ = -1;
  bool committed_ = false;
};

}  // namespace deltamesh::io
