// A trace written to a file (--trace PATH, Python's trace=): JSON Lines
// (docs/trace.md) into a temporary file renamed onto PATH by commit(), so a
// failed run leaves no partial trace behind. Errors throw IoError naming PATH.
#pragma once
#include <memory>
#include <string>

#include "deltamesh/trace.hpp"

namespace deltamesh {

class TraceFile {
 public:
  explicit TraceFile(const std::string& path);
  ~TraceFile();
  TraceFile(const TraceFile&) = delete;
  TraceFile& operator=(const TraceFile&) = delete;

  // The observer to attach (Plan::trace, TriangulateOptions::trace).
  TraceObserver& observer();
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace deltamesh
