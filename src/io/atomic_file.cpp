#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <system_error>

#include "deltamesh/errors.hpp"

namespace deltamesh::io {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  // O_EXCL makes the name this writer's own: other threads of this process
  // writing the same path at once take the next free number.
  const std::string stem = path_ + ".tmp." + std::to_string(::getpid()) + ".";
  int err = 0;
  for (int k = 0; k < kMaxTempAttempts; ++k) {
    temp_ = stem + std::to_string(k);
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ >= 0) return;
    err = errno;
    if (err != EEXIST) break;
  }
  const std::string temp = temp_;
  temp_.clear();  // not ours: the destructor must not remove it
  throw IoError("cannot create '" + path_ + "' (temporary file '" + temp + "'): " +
                std::generic_category().message(err));
}

AtomicFile::~AtomicFile() {
  if (!committed_) discard();
}

void AtomicFile::discard() noexcept {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
  if (!temp_.empty()) {
    ::unlink(temp_.c_str());
    temp_.clear();
  }
}

void AtomicFile::fail(const std::string& doing, int err) {
  discard();
  throw IoError("cannot " + doing + " '" + path_ + "': " + std::generic_category().message(err));
}

void AtomicFile::write(std::string_view data) {
  if (fd_ < 0) throw IoError("cannot write '" + path_ + "': the file is already closed");
  const char* p = data.data();
  std::size_t left = data.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write", errno);
    }
    if (n == 0) fail("write", EIO);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

void AtomicFile::commit() {
  if (fd_ < 0) throw IoError("cannot commit '" + path_ + "': the file is already closed");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("write", errno);
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) fail("rename the temporary file onto", errno);
  committed_ = true;
}

}  // namespace deltamesh::io
