// The progress callback API: throttled reports, first and last events, the
// terminal line (drawn only after the delay, erased at the end).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "deltamesh/progress.hpp"

using namespace deltamesh;

namespace {

struct Recorded {
  std::string phase, unit;
  std::size_t done, total;
  bool finished;
};

TEST(Progress, NoCallbackCostsNothingAndReportsNothing) {
  ProgressCallback none;
  ProgressReporter rep(none, "insert points", "points", 10);
  EXPECT_FALSE(rep.active());
  for (int i = 0; i < 100000; ++i) rep.advance();
  EXPECT_EQ(rep.done(), 100000u);
  rep.finish();
}

TEST(Progress, FirstPeriodicAndFinalEvents) {
  std::vector<Recorded> events;
  ProgressCallback cb = [&](const ProgressEvent& e) {
    events.push_back({std::string(e.phase), std::string(e.unit), e.done, e.total, e.finished});
  };
  {
    ProgressReporter rep(cb, "refine", "Steiner points", 0, std::chrono::milliseconds(5));
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(60);
    while (std::chrono::steady_clock::now() < until) rep.advance();
  }  // the destructor finishes
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events.front().done, 0u);
  EXPECT_FALSE(events.front().finished);
  EXPECT_EQ(events.front().phase, "refine");
  EXPECT_EQ(events.front().unit, "Steiner points");
  EXPECT_TRUE(events.back().finished);
  for (std::size_t i = 1; i < events.size(); ++i) EXPECT_GE(events[i].done, events[i - 1].done);
  for (std::size_t i = 0; i + 1 < events.size(); ++i) EXPECT_FALSE(events[i].finished);
  // Throttled: far fewer events than items.
  EXPECT_LT(events.size(), events.back().done / 100 + 20);
}

TEST(Progress, FinishReportsTheTotalOnce) {
  std::vector<Recorded> events;
  ProgressCallback cb = [&](const ProgressEvent& e) {
    events.push_back({std::string(e.phase), std::string(e.unit), e.done, e.total, e.finished});
  };
  ProgressReporter rep(cb, "recover segments", "segments", 500);
  rep.set(200);
  rep.finish();
  rep.finish();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_TRUE(events[1].finished);
  EXPECT_EQ(events[1].done, 500u);
  EXPECT_EQ(events[1].total, 500u);
}

TEST(Progress, TerminalLineFormat) {
  ProgressEvent e;
  e.phase = "insert points";
  e.unit = "points";
  e.done = 1234567;
  e.total = 10000000;
  e.seconds = 2.25;
  EXPECT_EQ(TerminalProgress::format(e), "  insert points: 1,234,567 / 10,000,000 points (12%) 2.2 s");
  e.total = 0;
  e.unit = "Steiner points";
  e.done = 999;
  EXPECT_EQ(TerminalProgress::format(e), "  insert points: 999 Steiner points 2.2 s");
}

TEST(Progress, TerminalDrawsAfterDelayAndErasesAtTheEnd) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    TerminalProgress term(f, std::chrono::milliseconds(1000), /*force=*/true);
    ASSERT_TRUE(term.enabled());
    ProgressEvent e;
    e.phase = "refine";
    e.unit = "triangles";
    e.done = 10;
    e.seconds = 0.5;  // before the delay: nothing
    term(e);
    e.done = 20;
    e.seconds = 1.5;
    term(e);
    e.done = 30;
    e.seconds = 2.5;
    term(e);
    e.finished = true;
    term(e);
  }
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  std::fclose(f);
  EXPECT_EQ(s.find("10 triangles"), std::string::npos);
  EXPECT_NE(s.find("\r  refine: 20 triangles 1.5 s"), std::string::npos) << s;
  EXPECT_NE(s.find("\r  refine: 30 triangles 2.5 s"), std::string::npos) << s;
  // Erased: ends with "\r", spaces, "\r".
  ASSERT_GE(s.size(), 2u);
  EXPECT_EQ(s.back(), '\r');
  EXPECT_EQ(s[s.size() - 2], ' ');
}

TEST(Progress, TerminalDisabledWhenNotATty) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  TerminalProgress term(f);
  EXPECT_FALSE(term.enabled());
  EXPECT_FALSE(static_cast<bool>(term.callback()));
  std::fclose(f);
}

}  // namespace
