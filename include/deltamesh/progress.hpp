// Progress reporting for long runs.
//
// The library never prints. An algorithm whose options struct carries a
// `ProgressCallback progress` reports counts through it: once when a phase
// starts (done = 0), at most every `interval` while it runs (throttled by a
// ProgressReporter, so the cost is one compare per work item), and once when
// it ends (finished = true). An empty callback costs nothing.
//
// The command line turns the events into a live line on a terminal
// (TerminalProgress), shown only for work longer than about a second, and
// into nothing at all with -Q.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>

namespace deltamesh {

struct ProgressEvent {
  std::string_view phase;   // "insert points", "recover segments", "refine", ...
  std::string_view unit;    // what is counted: "points", "segments", "Steiner points", "triangles"
  std::size_t done = 0;
  std::size_t total = 0;    // 0: unknown (refinement, where the end is not known in advance)
  double seconds = 0.0;     // since the phase started
  bool finished = false;    // the last event of the phase
};

using ProgressCallback = std::function<void(const ProgressEvent&)>;

// Throttles reports for one phase of an algorithm:
//
//   ProgressReporter rep(options.progress, "insert points", "points", n);
//   for (...) { ...; rep.advance(); }
//   rep.finish();   // or let the destructor do it
//
// advance() is an increment and a compare; the clock is read only every
// `check_every` items, and the callback is called when `interval` has passed
// since the last report.
class ProgressReporter {
 public:
  using Clock = std::chrono::steady_clock;

  ProgressReporter(const ProgressCallback& callback, std::string_view phase, std::string_view unit,
                   std::size_t total = 0, std::chrono::milliseconds interval = std::chrono::milliseconds(100));
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void advance(std::size_t n = 1) {
    done_ += n;
    if (done_ >= next_check_) check();
  }
  // Sets the count (for loops that know it directly).
  void set(std::size_t done) {
    done_ = done;
    if (done_ >= next_check_) check();
  }
  void set_total(std::size_t total) { total_ = total; }
  // Reports the final count (done = total when total is known and done is
  // behind) with finished = true. Called by the destructor if not before.
  void finish();

  std::size_t done() const { return done_; }
  bool active() const { return static_cast<bool>(callback_); }

 private:
  void check();
  void report(bool finished);

  ProgressCallback callback_;  // empty: nothing is done
  std::string phase_;
  std::string unit_;
  std::size_t done_ = 0;
  std::size_t total_ = 0;
  std::size_t next_check_;
  std::size_t check_every_ = 1024;
  Clock::time_point start_;
  Clock::time_point last_;        // last report
  Clock::time_point last_check_;  // last clock reading
  std::chrono::milliseconds interval_;
  bool finished_ = false;
};

// A live progress line for a terminal: "\r  refine: 1,234,567 Steiner
// points (42%) 3.1 s" redrawn in place, erased when the phase finishes.
// Nothing is drawn before `delay` has passed in a phase (short runs stay
// silent), nor when the stream is not a terminal (unless `force`).
class TerminalProgress {
 public:
  explicit TerminalProgress(std::FILE* stream = stderr, std::chrono::milliseconds delay = std::chrono::seconds(1),
                            bool force = false);
  // The callback to put into options structs. The TerminalProgress must
  // outlive it.
  ProgressCallback callback();
  void operator()(const ProgressEvent& event);
  bool enabled() const { return enabled_; }
  // Erases a line left on the terminal (call before printing other output).
  void clear();

  // The text of the line for an event (no "\r", no padding), for tests.
  static std::string format(const ProgressEvent& event);

 private:
  std::FILE* stream_;
  std::chrono::milliseconds delay_;
  bool enabled_;
  std::size_t shown_width_ = 0;  // characters of the line on screen, 0: none
};

}  // namespace deltamesh
