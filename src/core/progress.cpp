#include "deltamesh/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace deltamesh {

ProgressReporter::ProgressReporter(const ProgressCallback& callback, std::string_view phase, std::string_view unit,
                                   std::size_t total, std::chrono::milliseconds interval)
    : callback_(callback),
      phase_(phase),
      unit_(unit),
      total_(total),
      next_check_(callback ? std::size_t{1024} : static_cast<std::size_t>(-1)),
      interval_(interval) {
  if (!callback_) return;
  start_ = last_ = last_check_ = Clock::now();
  report(false);
}

ProgressReporter::~ProgressReporter() {
  try {
    finish();
  } catch (...) {
    // A throwing callback must not escape a destructor.
  }
}

void ProgressReporter::finish() {
  if (finished_) return;
  finished_ = true;
  if (!callback_) return;
  if (total_ != 0 && done_ < total_) done_ = total_;
  report(true);
}

void ProgressReporter::check() {
  next_check_ = done_ + check_every_;
  if (!callback_ || finished_) {
    next_check_ = static_cast<std::size_t>(-1);
    return;
  }
  const Clock::time_point now = Clock::now();
  // Adapt the stride so the clock is read roughly 10 to 40 times per interval.
  const auto since_check = now - last_check_;
  last_check_ = now;
  if (since_check < interval_ / 40 && check_every_ < (std::size_t{1} << 24)) {
    check_every_ *= 2;
  } else if (since_check > interval_ / 10 && check_every_ > 16) {
    check_every_ /= 2;
  }
  next_check_ = done_ + check_every_;
  if (now - last_ >= interval_) {
    last_ = now;
    report(false);
  }
}

void ProgressReporter::report(bool finished) {
  ProgressEvent ev;
  ev.phase = phase_;
  ev.unit = unit_;
  ev.done = done_;
  ev.total = total_;
  ev.seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  ev.finished = finished;
  callback_(ev);
}

// ---------------------------------------------------------------------------

TerminalProgress::TerminalProgress(std::FILE* stream, std::chrono::milliseconds delay, bool force)
    : stream_(stream), delay_(delay), enabled_(stream != nullptr && (force || ::isatty(::fileno(stream)) == 1)) {}

ProgressCallback TerminalProgress::callback() {
  if (!enabled_) return {};
  return [this](const ProgressEvent& e) { (*this)(e); };
}

namespace {

// 1234567 -> "1,234,567".
std::string grouped(std::size_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  const std::size_t len = digits.size();
  for (std::size_t i = 0; i < len; ++i) {
    if (i > 0 && (len - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace

std::string TerminalProgress::format(const ProgressEvent& e) {
  std::string s = "  ";
  s += e.phase;
  s += ": ";
  s += grouped(e.done);
  if (e.total != 0) {
    s += " / ";
    s += grouped(e.total);
  }
  if (!e.unit.empty()) {
    s += ' ';
    s += e.unit;
  }
  if (e.total != 0) {
    const double pct = 100.0 * static_cast<double>(std::min(e.done, e.total)) / static_cast<double>(e.total);
    char buf[32];
    std::snprintf(buf, sizeof buf, " (%.0f%%)", pct);
    s += buf;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, " %.1f s", e.seconds);
  s += buf;
  return s;
}

void TerminalProgress::operator()(const ProgressEvent& e) {
  if (!enabled_) return;
  if (e.finished) {
    clear();
    return;
  }
  if (e.seconds * 1000.0 < static_cast<double>(delay_.count())) return;
  const std::string line = format(e);
  std::string out = "\r" + line;
  if (line.size() < shown_width_) out.append(shown_width_ - line.size(), ' ');
  shown_width_ = line.size();
  std::fputs(out.c_str(), stream_);
  std::fflush(stream_);
}

void TerminalProgress::clear() {
  if (!enabled_ || shown_width_ == 0) return;
  std::string out = "\r";
  out.append(shown_width_, ' ');
  out += '\r';
  std::fputs(out.c_str(), stream_);
  std::fflush(stream_);
  shown_width_ = 0;
}

}  // namespace deltamesh
