// Adversarial inputs to the readers, the Delaunay step and the command line:
// every class of bad input gives a typed error naming what is wrong (and the
// CLI its documented exit code and message), never a crash, a hang, a huge
// allocation or a partial output file. docs/robustness.md lists the classes;
// keep the two in step.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "deltamesh/delaunay.hpp"
#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "deltamesh/triangle_io.hpp"
#include "deltamesh/validate.hpp"
#include "test_adversarial_util.hpp"

// ---------------------------------------------------------------------------
// Allocation watch: the largest single allocation made while a watch is
// active, to show that an absurd header count is never allocated for.

namespace {
std::atomic<bool> g_watching{false};
std::atomic<std::size_t> g_largest{0};

void note_allocation(std::size_t n) {
  if (!g_watching.load(std::memory_order_relaxed)) return;
  std::size_t cur = g_largest.load(std::memory_order_relaxed);
  while (n > cur && !g_largest.compare_exchange_weak(cur, n, std::memory_order_relaxed)) {
  }
}

void* allocate(std::size_t n) {
  note_allocation(n);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}

class AllocationWatch {
 public:
  AllocationWatch() {
    g_largest = 0;
    g_watching = true;
  }
  ~AllocationWatch() { g_watching = false; }
  std::size_t largest() const { return g_largest.load(); }
};
}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  note_allocation(n);
  return std::malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  note_allocation(n);
  return std::malloc(n == 0 ? 1 : n);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace dm = deltamesh;
using dm::test::CliResult;

namespace {

constexpr int kExitOk = 0, kExitInput = 2, kExitOutput = 4;

class Adversarial : public dm::test::TempDirTest {
 protected:
  // Runs `deltamesh -Q <switches> <file>` on `text` written to `file` and
  // expects exit code 2 with "deltamesh: <file>[:<line>]: ..." containing
  // `message`. line 0: the message names no line.
  void expect_input_error(const std::string& file, const std::string& text, std::size_t line,
                          const std::string& message, const std::string& switches = "") {
    write(file, text);
    const CliResult r = run("-Q " + switches + " " + file);
    EXPECT_EQ(r.code, kExitInput) << r.err;
    const std::string where = "deltamesh: " + file + (line ? ":" + std::to_string(line) : std::string()) + ": ";
    EXPECT_EQ(r.err.rfind(where, 0), 0u) << "expected the message to start with '" << where << "':\n" << r.err;
    EXPECT_CONTAINS(r.err, message);
    EXPECT_EQ(r.out, "");
    // Nothing written for an input that failed.
    const std::string base = file.substr(0, file.rfind('.'));
    EXPECT_FALSE(exists(base + ".1.node"));
    EXPECT_FALSE(exists(base + ".1.ele"));
  }

  // read_node on `text` throws ParseError at `line` mentioning `message`.
  void expect_node_parse_error(const std::string& text, std::size_t line, const std::string& message) {
    const std::string p = write("lib.node", text);
    try {
      dm::read_node(p);
      ADD_FAILURE() << "no ParseError; expected '" << message << "'";
    } catch (const dm::ParseError& e) {
      EXPECT_EQ(e.file(), p);
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_CONTAINS(e.problem(), message);
    }
  }
};

const std::string kTriangle = "3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n";

// The text of a .node file with the given points, numbered from 0.
std::string node_text(const std::vector<dm::Point>& pts) {
  std::string s = std::to_string(pts.size()) + " 2 0 0\n";
  char buf[96];
  for (std::size_t i = 0; i < pts.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%zu %.17g %.17g\n", i, pts[i].x, pts[i].y);
    s += buf;
  }
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------
// Coordinates: NaN, infinities, huge, subnormal

TEST_F(Adversarial, NanCoordinateIsAParseError) {
  expect_input_error("nan.node", "3 2 0 0\n0 0 0\n1 nan 0\n2 0 1\n", 3,
                     "the x coordinate of vertex 1 is not finite ('nan')");
  expect_input_error("nan2.node", "3 2 0 0\n0 0 0\n1 1 0\n2 0 -NaN\n", 4, "the y coordinate of vertex 2 is not finite");
}

TEST_F(Adversarial, InfiniteCoordinateIsAParseError) {
  expect_input_error("inf.node", "3 2 0 0\n0 0 0\n1 inf 0\n2 0 1\n", 3, "not finite ('inf')");
  expect_input_error("ninf.node", "3 2 0 0\n0 0 0\n1 1 0\n2 0 -infinity\n", 4, "not finite ('-infinity')");
}

TEST_F(Adversarial, LiteralBeyondDoubleRangeIsAParseError) {
  expect_input_error("big.node", "3 2 0 0\n0 0 0\n1 1e400 0\n2 0 1\n", 3,
                     "'1e400' is out of range (expected the x coordinate of vertex 1)");
}

TEST_F(Adversarial, CoordinatesTooFarApartInMagnitudeAreAnInputError) {
  // Any finite magnitude is meshed (run() scales by a power of two), but a
  // nonzero coordinate about 2^400 below the largest is beyond the exact
  // predicates beside it. The message names the small point and the ratio.
  expect_input_error("huge.node", "3 2 0 0\n0 0 0\n1 1e121 0\n2 0 1\n", 4,
                     "huge.node:4: vertex 2: coordinate y (1) is nonzero but too small beside the largest");
  expect_input_error("huge2.node", "3 2 0 0\n0 0 0\n1 0 1\n2 0 -1e300\n", 3, "ratio of about 2^400");
  write("far.node", "3 2 0 0\n0 0 0\n1 1e300 0\n2 0 1e300\n");
  EXPECT_EQ(run("-QC far.node").code, kExitOk);
}

TEST_F(Adversarial, CoordinatesAtTheLimitsOfTheRangeMesh) {
  // 2^200 and 2^-200 themselves are accepted and meshed exactly.
  const double big = std::ldexp(1.0, 200), small = std::ldexp(1.0, -200);
  write("edge.node", node_text({{0, 0}, {big, 0}, {0, big}, {small, small}, {-big, -small}}));
  const CliResult r = run("-QC edge.node");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(exists("edge.1.ele"));
}

TEST_F(Adversarial, SubnormalCoordinateIsAnInputError) {
  expect_input_error("denormal.node", "3 2 0 0\n0 0 0\n1 1 4.9406564584124654e-324\n2 0 1\n", 3,
                     "denormal.node:3: vertex 1: coordinate y (4.9406564584124654e-324) is nonzero but too small");
  expect_input_error("denormal2.node", "3 2 0 0\n0 0 0\n1 1e-310 0\n2 0 1\n", 3, "ratio of about 2^400");
  // Subnormal coordinates alone are a shape at a tiny scale: meshed.
  write("subnormal.node", "3 2 0 0\n0 0 0\n1 1e-310 0\n2 0 1e-310\n");
  EXPECT_EQ(run("-QC subnormal.node").code, kExitOk);
  // Negative zero is zero.
  write("negzero.node", "3 2 0 0\n0 -0 -0.0\n1 1 0\n2 0 1\n");
  EXPECT_EQ(run("-QC negzero.node").code, kExitOk);
}

TEST_F(Adversarial, DelaunayRejectsBadCoordinatesWithTheirIndex) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // 1e-310 beside 1 is beyond the exact predicates' reach (2^400) in any
  // frame; 1e61 or 2^-201 beside 1 are meshed in an exact power-of-two
  // frame (issue 20: delaunay() called directly normalises too).
  for (const dm::Point bad : {dm::Point{nan, 0}, dm::Point{0, inf}, dm::Point{-inf, 1}, dm::Point{0, 1e-310}}) {
    const std::vector<dm::Point> pts = {{0, 0}, {1, 0}, {0, 1}, bad, {1, 1}};
    try {
      dm::delaunay(pts);
      ADD_FAILURE() << "no InputError for (" << bad.x << ", " << bad.y << ")";
    } catch (const dm::InputError& e) {
      EXPECT_EQ(e.index(), 3u) << e.what();
      EXPECT_CONTAINS(e.what(), "point 3");
    }
  }
  for (const dm::Point far : {dm::Point{1e61, 0}, dm::Point{0x1p-201, 1}}) {
    const std::vector<dm::Point> pts = {{0, 0}, {1, 0}, {0, 1}, far, {1, 1}};
    const dm::Mesh m = dm::delaunay(pts);
    EXPECT_GE(m.num_triangles(), 3u);
    for (dm::VertexId v = 0; v < pts.size(); ++v) EXPECT_EQ(m.point(v), pts[v]);
  }
}

// ---------------------------------------------------------------------------
// Counts: negative, absurd, larger than the file

TEST_F(Adversarial, NegativeCountsAreParseErrors) {
  expect_input_error("neg.node", "-3 2 0 0\n", 1, "vertex count -3 is negative");
  expect_input_error("negattr.node", "3 2 -1 0\n0 0 0\n1 1 0\n2 0 1\n", 1, "attribute count -1 is negative");
  expect_input_error("negseg.poly", kTriangle + "-1 0\n0\n", 5, "segment count -1 is negative", "-p");
  expect_input_error("neghole.poly", kTriangle + "0 0\n-2\n", 6, "hole count -2 is negative", "-p");
}

TEST_F(Adversarial, AbsurdVertexCountIsRejectedQuicklyWithoutAllocating) {
  const std::string text = "1000000000000 2 0 0\n0 0 0\n1 1 0\n";
  expect_input_error("absurd.node", text, 1, "header announces 1000000000000 vertices but the file has only 2 lines left");
  // Library: no allocation anywhere near the announced size, and fast.
  const std::string p = write("lib.node", text);
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t largest = 0;
  {
    AllocationWatch watch;
    EXPECT_THROW(dm::read_node(p), dm::ParseError);
    largest = watch.largest();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(largest, std::size_t{1} << 20) << "an allocation of " << largest << " bytes";
  EXPECT_LT(seconds, 1.0);
}

TEST_F(Adversarial, AbsurdCountsInEverySectionAndFormat) {
  const std::string big = "999999999999999";
  struct Case {
    std::string name, text;
    std::size_t line;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"attrs.node", "3 2 " + big + " 0\n0 0 0\n", 1, "attribute count " + big + " is larger than the file"},
      {"segs.poly", kTriangle + big + " 0\n0 0 1\n", 5, "header announces " + big + " segments"},
      {"holes.poly", kTriangle + "0 0\n" + big + "\n0 0.1 0.1\n", 6, "header announces " + big + " holes"},
      {"regions.poly", kTriangle + "0 0\n0\n" + big + "\n0 0.1 0.1 1\n", 7, "header announces " + big + " regions"},
      {"tris.ele", big + " 3 0\n0 0 1 2\n", 1, "header announces " + big + " triangles"},
      {"eleattrs.ele", "1 3 " + big + "\n0 0 1 2\n", 1, "attribute count " + big + " is larger than the file"},
      {"tris.area", big + "\n0 1\n", 1, "header announces " + big + " triangles"},
      {"over.node", "99999999999999999999 2 0 0\n", 1, "is out of range"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string p = write(c.name, c.text);
    std::size_t largest = 0;
    try {
      AllocationWatch watch;
      try {
        if (c.name.ends_with(".node")) dm::read_node(p);
        if (c.name.ends_with(".poly")) dm::read_poly(p);
        if (c.name.ends_with(".ele")) dm::read_ele(p, 0);
        if (c.name.ends_with(".area")) dm::read_area(p);
      } catch (...) {
        largest = watch.largest();
        throw;
      }
      ADD_FAILURE() << "no ParseError";
    } catch (const dm::ParseError& e) {
      EXPECT_EQ(e.line(), c.line) << e.what();
      EXPECT_CONTAINS(e.problem(), c.message);
    }
    EXPECT_LT(largest, std::size_t{1} << 20) << "an allocation of " << largest << " bytes";
  }
}

TEST_F(Adversarial, CountLargerThanTheFile) {
  expect_input_error("short.node", "5 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", 1, "header announces 5 vertices");
  // A count the cheap size test lets through ends at the end of the file.
  std::string text = "40 2 0 0\n";
  for (int i = 0; i < 3; ++i) text += std::to_string(i) + " 1 2 # " + std::string(100, '.') + "\n";
  expect_node_parse_error(text, 1, "header announces 40 vertices but the file ends after 3");
  expect_input_error("shortseg.poly", kTriangle + "3 0\n0 0 1\n", 5, "header announces 3 segments", "-p");
}

TEST_F(Adversarial, EmptyAndCommentOnlyFiles) {
  expect_input_error("empty.node", "", 1, "the file holds no data");
  expect_input_error("comments.node", "# nothing\n\n   # here\n", 3, "the file holds no data");
  expect_input_error("zero.node", "0 2 0 0\n", 0, "no triangle can be made");
}

// ---------------------------------------------------------------------------
// Tokens, ids and references

TEST_F(Adversarial, NonNumericTokens) {
  expect_input_error("word.node", "3 2 0 0\n0 0 0\n1 abc 0\n2 0 1\n", 3,
                     "'abc' is not a number (expected the x coordinate of vertex 1)");
  expect_input_error("hex.node", "3 2 0 0\n0 0 0\n1 1 0x10\n2 0 1\n", 3, "'0x10' is not a number");
  expect_input_error("count.node", "three 2 0 0\n", 1, "'three' is not a number (expected vertex count)");
  expect_input_error("frac.node", "2.5 2 0 0\n", 1, "'2.5' is not an integer");
  expect_input_error("id.node", "3 2 0 0\n0 0 0\nx 1 0\n2 0 1\n", 3, "'x' is not a number");
  expect_input_error("marker.node", "3 2 0 1\n0 0 0 1\n1 1 0 1\n2 0 1 one\n", 4, "'one' is not a number");
  // Bytes of a binary file are shown escaped: no control character or NUL
  // (which would cut the message short) reaches the terminal.
  expect_input_error("binary.node", std::string("3 2 0 0\n0 0 0\n1 \x01\xff\x00 0\n2 0 1\n", 26), 3,
                     "'\\x01\\xff\\x00' is not a number (expected the x coordinate of vertex 1)");
  // A megabyte-long token is shown truncated.
  expect_input_error("long.node", "3 2 0 0\n0 0 0\n1 " + std::string(1 << 20, '7') + "x 0\n2 0 1\n", 3,
                     "'" + std::string(40, '7') + "...' is not a number");
  const CliResult r = run("-Q long.node");
  EXPECT_LT(r.err.size(), 200u);
}

TEST_F(Adversarial, MissingFields) {
  expect_input_error("fields.node", "3 2 0 0\n0 0 0\n1 1\n2 0 1\n", 3, "expected 2 coordinates for vertex 1, found 1");
  expect_input_error("attr.node", "3 2 1 0\n0 0 0 5\n1 1 0\n2 0 1 5\n", 3, "expected 1 attribute for vertex 1");
  expect_input_error("dim.node", "3 3 0 0\n", 1, "dimension is 3, but only 2 is supported");
}

TEST_F(Adversarial, DuplicateAndOutOfOrderIds) {
  expect_input_error("dup.node", "3 2 0 0\n0 0 0\n1 1 0\n1 0 1\n", 4,
                     "duplicate vertex number 1: vertices must be numbered consecutively, expected 2");
  expect_input_error("order.node", "3 2 0 0\n0 0 0\n2 1 0\n1 0 1\n", 3, "vertex number 2 is out of order");
  expect_input_error("first.node", "3 2 0 0\n5 0 0\n6 1 0\n7 0 1\n", 2,
                     "the first vertex is numbered 5, but vertices must be numbered from 0 or 1");
  expect_input_error("dupseg.poly", kTriangle + "2 0\n0 0 1\n0 1 2\n0\n", 7, "duplicate segment number 0", "-p");
}

TEST_F(Adversarial, IndicesOutOfRange) {
  expect_input_error("range.poly", kTriangle + "1 0\n0 0 5\n0\n", 6,
                     "segment 0 refers to vertex 5, but vertices are numbered 0..2", "-p");
  expect_input_error("negref.poly", kTriangle + "1 0\n0 -1 2\n0\n", 6, "segment 0 refers to vertex -1", "-p");
  expect_input_error("bigref.poly", kTriangle + "1 0\n0 0 99999999999999999999\n0\n", 6, "is out of range", "-p");
  // .ele references (library: the CLI's -r checks them against the .node).
  const std::string p = write("t.ele", "1 3 0\n0 0 1 -4\n");
  try {
    dm::read_ele(p, 0);
    ADD_FAILURE() << "no ParseError";
  } catch (const dm::ParseError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_CONTAINS(e.problem(), "triangle 0 refers to vertex -4, but vertices are numbered from 0");
  }
}

TEST_F(Adversarial, TrailingGarbage) {
  expect_input_error("trail.node", kTriangle + "3 5 5\n", 5, "unexpected data after the 3 vertices announced on line 1");
}

// ---------------------------------------------------------------------------
// Degenerate geometry

TEST_F(Adversarial, AllPointsCollinear) {
  expect_input_error("line3.node", "3 2 0 0\n0 0 0\n1 1 1\n2 2 2\n", 0,
                     "no triangle can be made: all 3 points are collinear");
  // An exact line (y = 2x + 1 on integers) of 1000 points, in scrambled order.
  std::vector<dm::Point> pts;
  for (int i = 0; i < 1000; ++i) {
    const int k = (i * 337) % 1000;
    pts.push_back({static_cast<double>(k), 2.0 * k + 1});
  }
  expect_input_error("line1000.node", node_text(pts), 0, "all 1000 points are collinear");
  EXPECT_THROW(dm::delaunay(pts), dm::InputError);
}

TEST_F(Adversarial, AllPointsIdentical) {
  expect_input_error("same.node", "3 2 0 0\n0 1 1\n1 1 1\n2 1 1\n", 0,
                     "the input has 3 points but fewer than 3 distinct ones");
  // Two distinct points: collinear too.
  expect_input_error("two.node", "4 2 0 0\n0 1 1\n1 1 1\n2 2 1\n3 2 1.0\n", 0, "no triangle can be made");
}

TEST_F(Adversarial, NearlyCollinearPointsMeshExactly) {
  // Three points off a line by one unit in the last place, plus the line.
  const double e = std::nextafter(1.0, 2.0);
  write("near.node", node_text({{0, 0}, {1, 1}, {2, 2}, {3, 3}, {1, e}, {2, std::nextafter(2.0, 0.0)}}));
  const CliResult r = run("-QC near.node");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  const dm::Mesh m = dm::delaunay(std::vector<dm::Point>{{0, 0}, {1, 1}, {2, 2}, {3, 3}, {1, e}});
  EXPECT_TRUE(dm::check(m).ok());
  EXPECT_EQ(m.num_triangles(), 3u);  // the hull is the thin triangle (0, 3, 4) fanned at 1 and 2
}

TEST_F(Adversarial, NearlyCoincidentVertices) {
  // Neighbours one ulp apart, at several magnitudes: all distinct, all used.
  for (const double s : {1.0, 0x1p-190, 0x1p190, 1e-9, 1e9}) {
    SCOPED_TRACE(s);
    std::vector<dm::Point> pts = {{s, s}, {2 * s, s}, {s, 2 * s}, {2 * s, 2 * s}};
    for (int k = 0; k < 4; ++k) {
      const dm::Point q = pts[k];
      pts.push_back({std::nextafter(q.x, 1e300), q.y});
      pts.push_back({q.x, std::nextafter(q.y, -1e300)});
    }
    dm::DelaunayStats st;
    const dm::Mesh m = dm::delaunay(pts, {}, &st);
    const dm::CheckReport rep = dm::check(m);
    EXPECT_TRUE(rep.ok()) << rep.summary();
    EXPECT_EQ(st.duplicates, 0u);
    EXPECT_EQ(rep.vertices_used, pts.size());
  }
  write("close.node", node_text({{1, 1}, {std::nextafter(1.0, 2.0), 1}, {1, std::nextafter(1.0, 2.0)}, {2, 2}}));
  EXPECT_EQ(run("-QC close.node").code, kExitOk);
}

TEST_F(Adversarial, TinyAngles) {
  // A needle triangle with an angle of ~1e-15 rad, and a fan of such needles.
  write("needle.node", node_text({{0, 0}, {1, 0}, {1, 1e-15}}));
  CliResult r = run("-QC needle.node");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  std::vector<dm::Point> fan = {{0, 0}};
  for (int i = 1; i <= 50; ++i) fan.push_back({1.0, i * 1e-14});
  write("fan.node", node_text(fan));
  r = run("-QC fan.node");
  EXPECT_EQ(r.code, kExitOk) << r.err;
}

TEST_F(Adversarial, MillionDuplicatePoints) {
  // 10^6 copies of one point inside a triangle (10^5 under sanitizers).
  const std::size_t copies = dm::test::quick_tests() ? 100000 : 1000000;
  std::vector<dm::Point> pts = {{0, 0}, {1, 0}, {0, 1}};
  pts.resize(3 + copies, dm::Point{0.25, 0.25});
  dm::DelaunayStats st;
  const auto t0 = std::chrono::steady_clock::now();
  const dm::Mesh m = dm::delaunay(pts, {}, &st);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(st.duplicates, copies - 1);
  EXPECT_EQ(m.num_triangles(), 3u);
  EXPECT_TRUE(dm::check(m).ok());
  EXPECT_LT(seconds, 30.0);

  // The same through the CLI, -j dropping the duplicates from the output.
  std::string text = std::to_string(pts.size()) + " 2 0 0\n0 0 0\n1 1 0\n2 0 1\n";
  text.reserve(text.size() + copies * 18);
  for (std::size_t i = 3; i < pts.size(); ++i) text += std::to_string(i) + " 0.25 0.25\n";
  write("dups.node", text);
  CliResult r = run("-QCj dups.node");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(dm::test::slurp(dir_ / "dups.1.node").substr(0, 8), "4 2 0 1\n");

  // Only identical points: no triangle.
  std::string same = std::to_string(copies) + " 2 0 0\n";
  for (std::size_t i = 0; i < copies; ++i) same += std::to_string(i) + " 7 7\n";
  write("same.node", same);
  r = run("-Q same.node");
  EXPECT_EQ(r.code, kExitInput);
  EXPECT_CONTAINS(r.err, "fewer than 3 distinct ones");
}

// ---------------------------------------------------------------------------
// Files and output

TEST_F(Adversarial, MissingInputFile) {
  const CliResult r = run("-Q nothing.node");
  EXPECT_EQ(r.code, kExitInput);
  EXPECT_CONTAINS(r.err, "deltamesh: cannot open input file 'nothing.node': no such file");
}

TEST_F(Adversarial, InputIsADirectory) {
  std::filesystem::create_directory(dir_ / "dir.node");
  const CliResult r = run("-Q dir.node");
  EXPECT_EQ(r.code, kExitInput) << r.err;
  EXPECT_CONTAINS(r.err, "dir.node");
  EXPECT_CONTAINS(r.err, "directory");
}

TEST_F(Adversarial, UnwritableOutputExitsWith4AndLeavesNoPartialFile) {
  // The output file's name is taken by a directory: the write fails
  // whoever runs the test (root included).
  write("in.node", kTriangle);
  std::filesystem::create_directory(dir_ / "in.1.node");
  CliResult r = run("-Q in.node");
  EXPECT_EQ(r.code, kExitOutput) << r.err;
  EXPECT_CONTAINS(r.err, "in.1.node");
  EXPECT_EQ(listing(), (std::vector<std::string>{"in.1.node", "in.node"}));  // no temporary, no .ele
  EXPECT_TRUE(std::filesystem::is_empty(dir_ / "in.1.node"));

  // An output directory that does not exist.
  r = run("-Q --svg missing/dir/pic.svg in.node -N -E");
  EXPECT_EQ(r.code, kExitOutput) << r.err;
  EXPECT_CONTAINS(r.err, "missing/dir/pic.svg");

  // A directory without write permission (only meaningful when not root).
  if (::geteuid() != 0) {
    std::filesystem::create_directory(dir_ / "ro");
    write("ro/in.node", kTriangle);
    std::filesystem::permissions(dir_ / "ro", std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    r = run("-Q ro/in.node");
    std::filesystem::permissions(dir_ / "ro", std::filesystem::perms::owner_all);
    EXPECT_EQ(r.code, kExitOutput) << r.err;
    EXPECT_CONTAINS(r.err, "ro/in.1.node");
    EXPECT_EQ(listing("ro"), (std::vector<std::string>{"in.node"}));
  }
}

// ---------------------------------------------------------------------------
// Domains: holes, regions, segments

namespace {
// The square [0,4]^2 bounded by four segments; append holes and regions.
const std::string kSquare = "4 2 0 0\n0 0 0\n1 4 0\n2 4 4\n3 0 4\n4 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n";

// Triangles in an .ele file the CLI wrote (its header's first number).
long triangles_in(const std::filesystem::path& ele) {
  const std::string text = dm::test::slurp(ele);
  return std::strtol(text.c_str(), nullptr, 10);
}
}  // namespace

TEST_F(Adversarial, HoleOutsideTheDomainIsIgnoredWithAWarning) {
  write("hole.poly", kSquare + "2\n0 9 9\n1 -1e300 0\n");
  const CliResult r = run("-p hole.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "deltamesh: warning: hole points 0 at (9, 9), 1 at (-1.0000000000000001e+300, 0) ignored "
                         "(outside the convex hull, on a vertex or on a segment)");
  EXPECT_EQ(triangles_in(dir_ / "hole.1.ele"), 2);
}

TEST_F(Adversarial, HoleOnAVertexOrASegmentIsIgnored) {
  write("hole.poly", kSquare + "2\n0 0 0\n1 2 0\n");
  const CliResult r = run("-p hole.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "hole points 0 at (0, 0), 1 at (2, 0) ignored");
  EXPECT_EQ(triangles_in(dir_ / "hole.1.ele"), 2);
}

TEST_F(Adversarial, RegionPointInAHoleIsIgnoredWithAWarning) {
  // An inner square [1,3]^2 with a hole point; the region point is in it.
  const std::string text =
      "8 2 0 0\n0 0 0\n1 4 0\n2 4 4\n3 0 4\n4 1 1\n5 3 1\n6 3 3\n7 1 3\n"
      "8 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n4 4 5\n5 5 6\n6 6 7\n7 7 4\n1\n0 2 2\n2\n0 2.5 2.5 7 -1\n1 0.5 0.5 3 -1\n";
  write("region.poly", text);
  const CliResult r = run("-pA region.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "deltamesh: warning: region point 0 at (2.5, 2.5) ignored (outside the domain, on a vertex or on a segment)");
  EXPECT_EQ(triangles_in(dir_ / "region.1.ele"), 8);
}

TEST_F(Adversarial, EmptyDomainIsASuccessWithAWarning) {
  // A hole point inside the only region, and an open boundary: nothing is left.
  write("hole_everywhere.poly", kSquare + "1\n0 2 2\n");
  CliResult r = run("-pC hole_everywhere.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "every triangle was removed: the domain is empty");
  EXPECT_EQ(triangles_in(dir_ / "hole_everywhere.1.ele"), 0);
  write("open.poly", "3 2 0 0\n0 0 0\n1 4 0\n2 0 4\n1 0\n0 0 1\n0\n");
  r = run("-p open.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "the domain is empty");
  EXPECT_EQ(triangles_in(dir_ / "open.1.ele"), 0);
}

TEST_F(Adversarial, CrossingSegmentsAreSplitOrRejectedUnderStrict) {
  const std::string text = "4 2 0 0\n0 0 0\n1 2 0\n2 0 2\n3 2 2\n2 0\n0 0 3\n1 1 2\n0\n";
  write("cross.poly", text);
  CliResult r = run("-pcC cross.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_EQ(triangles_in(dir_ / "cross.1.ele"), 4);  // split at (1, 1)
  expect_input_error("strict.poly", text, 0,
                     "segments 0 and 1 cross (--strict; without it they are split where they cross)", "-p --strict");
}

TEST_F(Adversarial, ZeroLengthSegmentIsIgnoredWithAWarning) {
  write("zero.poly", "5 2 0 0\n0 0 0\n1 4 0\n2 4 4\n3 0 4\n4 4 4\n5 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n4 2 4\n0\n");
  const CliResult r = run("-pC zero.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
  EXPECT_CONTAINS(r.err, "1 zero-length segment ignored");
}

TEST_F(Adversarial, ManySegmentsThroughOnePoint) {
  // 200 segments crossing at the centre of a square: one vertex added
  // where they all cross, and a valid mesh.
  std::string text = "404 2 0 0\n0 -1 -1\n1 1 -1\n2 1 1\n3 -1 1\n";
  for (int i = 0; i < 200; ++i) {
    const double a = 3.141592653589793 * i / 200;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%d %.17g %.17g\n%d %.17g %.17g\n", 4 + 2 * i, 0.9 * std::cos(a), 0.9 * std::sin(a),
                  5 + 2 * i, -0.9 * std::cos(a), -0.9 * std::sin(a));
    text += buf;
  }
  text += "204 0\n0 0 1\n1 1 2\n2 2 3\n3 3 0\n";
  for (int i = 0; i < 200; ++i)
    text += std::to_string(4 + i) + " " + std::to_string(4 + 2 * i) + " " + std::to_string(5 + 2 * i) + "\n";
  text += "0\n";
  write("star.poly", text);
  const CliResult r = run("-pQC star.poly");
  EXPECT_EQ(r.code, kExitOk) << r.err;
}

TEST_F(Adversarial, MalformedGeoJsonNamesLineAndColumn) {
  write("bad.geojson", "{\"type\": \"Polygon\",\n \"coordinates\": [[[0, 0], [1, 0], \"x\"]]}");
  CliResult r = run("-Q bad.geojson");
  EXPECT_EQ(r.code, kExitInput) << r.err;
  EXPECT_CONTAINS(r.err, "deltamesh: bad.geojson:2:");
  EXPECT_CONTAINS(r.err, "a position must be an array of 2 or 3 numbers");
  write("cut.geojson", "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1, 0], [0, 1], [0, 0]]");
  r = run("-Q cut.geojson");
  EXPECT_EQ(r.code, kExitInput) << r.err;
  EXPECT_CONTAINS(r.err, "unexpected end of file");
  write("range.geojson", "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1e999, 0], [0, 1], [0, 0]]]}");
  r = run("-Q range.geojson");
  EXPECT_EQ(r.code, kExitInput) << r.err;
  EXPECT_CONTAINS(r.err, "number 1e999 is out of range");
  write("huge.geojson", "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1e200, 0], [0, 1], [0, 0]]]}");
  r = run("-Q huge.geojson");
  EXPECT_EQ(r.code, kExitInput) << r.err;
  EXPECT_CONTAINS(r.err, "too small beside the largest");
  // Deeply nested arrays: an error, not a stack overflow.
  write("deep.geojson", "{\"type\": \"Polygon\", \"coordinates\": " + std::string(100000, '[') + "}");
  r = run("-Q deep.geojson");
  EXPECT_EQ(r.code, kExitInput) << r.err;
}
