// TraceFile: JsonLinesTrace into an AtomicFile.
#include "deltamesh/trace_file.hpp"

#include "io/atomic_file.hpp"

namespace deltamesh {

struct TraceFile::Impl {
  explicit Impl(const std::string& path) : file(path), trace([this](std::string_view s) { file.write(s); }) {}
  io::AtomicFile file;
  JsonLinesTrace trace;
};

TraceFile::TraceFile(const std::string& path) : impl_(std::make_unique<Impl>(path)) {}
TraceFile::~TraceFile() = default;

TraceObserver& TraceFile::observer() { return impl_->trace; }

void TraceFile::commit() {
  impl_->trace.finish();
  impl_->file.commit();
}

}  // namespace deltamesh
