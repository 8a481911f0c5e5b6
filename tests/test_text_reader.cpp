// The text reader's fast paths: the decimal parser must give exactly what
// std::from_chars gives whenever it answers, a mapped file must read like
// the same bytes in memory, and the fast .node line path must leave errors
// (file:line and wording) to the general path unchanged.
#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/triangle_io.hpp"
#include "io/text_reader.hpp"

namespace {

using namespace deltamesh;
namespace fs = std::filesystem;

// Checks parse_decimal_prefix against std::from_chars on s; returns whether
// the fast path answered.
bool agrees_with_from_chars(const std::string& s) {
  const char* first = s.data();
  const char* last = first + s.size();
  double fast = -1.0;
  const char* end = io::parse_decimal_prefix(first, last, fast);
  if (end == nullptr) return false;
  double slow = -2.0;
  const auto r = std::from_chars(first, last, slow);
  EXPECT_EQ(r.ec, std::errc()) << s;
  EXPECT_EQ(end, r.ptr) << s;
  EXPECT_EQ(std::bit_cast<std::uint64_t>(fast), std::bit_cast<std::uint64_t>(slow))
      << s << ": fast " << fast << ", from_chars " << slow;
  return true;
}

std::string shortest(double v) {
  char buf[64];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

std::string printf_g(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

TEST(DecimalPrefix, AgreesWithFromCharsOnRandomDoubles) {
  std::mt19937_64 rng(20261202);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> exp2(-80, 80);
  int answered = 0, total = 0;
  for (int i = 0; i < 200000; ++i) {
    // Uniform in [0,1) (the benchmark's inputs), then spread over magnitudes.
    const double u = unit(rng);
    const double v = (i % 2 ? -1.0 : 1.0) * std::ldexp(u, i % 3 ? 0 : exp2(rng));
    for (const std::string& s : {shortest(v), printf_g("%.17g", v), printf_g("%.15g", v), printf_g("%.6e", v),
                                 printf_g("%.19g", v), printf_g("%.25g", v)}) {
      answered += agrees_with_from_chars(s);
      ++total;
    }
  }
  // The fast path must carry almost all of it (else the test would pass
  // without checking anything and reading would be slow).
  EXPECT_GT(answered, total * 3 / 4);
}

TEST(DecimalPrefix, AnswersShortestUniformCoordinates) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int answered = 0;
  for (int i = 0; i < 100000; ++i) answered += agrees_with_from_chars(shortest(unit(rng)));
  EXPECT_GT(answered, 99000);
}

TEST(DecimalPrefix, AgreesOnRandomDigitStrings) {
  std::mt19937_64 rng(99);
  const std::string alphabet = "0123456789";
  for (int i = 0; i < 200000; ++i) {
    std::string s;
    if (rng() % 4 == 0) s += '-';
    const int n = 1 + static_cast<int>(rng() % 24);
    const int dot = static_cast<int>(rng() % (n + 2)) - 1;  // -1: none
    for (int k = 0; k < n; ++k) {
      if (k == dot) s += '.';
      s += alphabet[rng() % (rng() % 3 == 0 ? 1 : 10)];  // runs of zeros too
    }
    if (rng() % 3 == 0) {
      s += rng() % 2 ? 'e' : 'E';
      const int r = static_cast<int>(rng() % 4);
      if (r == 1) s += '-';
      if (r == 2) s += '+';
      s += std::to_string(rng() % 40);
    }
    if (rng() % 5 == 0) s += " 1";
    agrees_with_from_chars(s);
  }
}

TEST(DecimalPrefix, HandsOddSpellingsAndTiesToFromChars) {
  for (const char* s : {"", "-", ".", "-.", "+1", "e5", "1e", "1e+", "1.5e-", "nan", "inf", "-infinity",
                        "12345678901234567890", "1e400", "1e-400", "9007199254740993", "9007199254740995"}) {
    double v = 0.0;
    EXPECT_EQ(io::parse_decimal_prefix(s, s + std::strlen(s), v), nullptr) << s;
  }
  // Exact halfway cases between two doubles (2^53 + 1 and + 3): from_chars
  // rounds them to even, and parse_double returns that.
  double v = 0.0;
  ASSERT_EQ(io::parse_double("9007199254740993", v), io::NumberStatus::Ok);
  EXPECT_EQ(v, 9007199254740992.0);
  ASSERT_EQ(io::parse_double("9007199254740995", v), io::NumberStatus::Ok);
  EXPECT_EQ(v, 9007199254740996.0);
  for (const std::string s : {"0", "-0", "0.0", "-0.000", "000123.2500", "5.", ".5", "-.5", "1E5", "1e+05", "2.5e-3x",
                              "1.2.3", "0x1p3", "0.1", "0.3", "123456789012345678e-5", "0.000000000000000000000000001"}) {
    EXPECT_TRUE(agrees_with_from_chars(s)) << s;
  }
  ASSERT_NE(io::parse_decimal_prefix("-0", "-0" + 2, v), nullptr);
  EXPECT_TRUE(std::signbit(v));
}

class TextReaderFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("dm_text_reader_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  // The ParseError read_node throws on `text` ("" when none).
  std::string node_error(const std::string& text) const {
    const std::string p = write("e.node", text);
    try {
      read_node(p);
    } catch (const ParseError& e) {
      EXPECT_EQ(e.file(), p);
      return std::to_string(e.line()) + ": " + e.problem();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(TextReaderFiles, MappedFileTokenisesLikeMemory) {
  const std::string text = "\xEF\xBB\xBF# c\r\n\r\n 3 2 0 1 # h\r\n1 0.5 -2e-3 7\n\t2\t+4 .5 -1 extra\n3 1e2 5. 0";
  const std::string p = write("a.node", text);
  io::TextReader mapped = io::TextReader::open(p);
  io::TextReader memory("mem", text);
  while (true) {
    const bool a = mapped.next_line(), b = memory.next_line();
    ASSERT_EQ(a, b);
    if (!a) break;
    EXPECT_EQ(mapped.line(), memory.line());
    ASSERT_EQ(mapped.size(), memory.size());
    for (std::size_t i = 0; i < mapped.size(); ++i) EXPECT_EQ(mapped.token(i), memory.token(i));
  }
  EXPECT_EQ(mapped.last_line(), memory.last_line());
  const Pslg g = read_node(p);
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.points[0], (Point{0.5, -2e-3}));
  EXPECT_EQ(g.points[1], (Point{4.0, 0.5}));
  EXPECT_EQ(g.points[2], (Point{100.0, 5.0}));
  EXPECT_EQ(g.point_markers, (std::vector<int>{7, -1, 0}));
}

TEST_F(TextReaderFiles, EmptyAndKernelFilesAreRead) {
  const std::string empty = write("empty.node", "");
  io::TextReader r = io::TextReader::open(empty);
  EXPECT_FALSE(r.next_line());
  // /proc files report size 0 but have content: read, not mapped.
  if (fs::exists("/proc/self/status")) {
    io::TextReader s = io::TextReader::open("/proc/self/status");
    EXPECT_TRUE(s.next_line());
  }
  EXPECT_THROW(io::TextReader::open((dir_ / "missing.node").string()), IoError);
  EXPECT_THROW(io::TextReader::open(dir_.string()), IoError);
}

TEST_F(TextReaderFiles, FastLinesMatchGeneralParsing) {
  // Every line mixes in a spelling the fast path hands on (signs, long
  // mantissas, exponents, ties, infinities' neighbours, CRLF, comments).
  std::string text = "8 2 0 1\n";
  const char* coords[] = {"0.1 0.2",         "+1 -0",        "1e-5 5E+2",          "12345678901234567890 0.5",
                          "9007199254740993 0.3", "1.5\t-2.25", "0.000000000000000000000000000001 7", "5. .5"};
  for (int i = 0; i < 8; ++i)
    text += std::to_string(i + 1) + " " + coords[i] + " " + std::to_string(i - 3) + (i % 2 ? "\r\n" : " # c\n");
  const Pslg g = read_node(write("b.node", text));
  ASSERT_EQ(g.points.size(), 8u);
  for (int i = 0; i < 8; ++i) {
    const std::string c = coords[i];
    const std::size_t sep = c.find_first_of(" \t");
    double x, y;
    ASSERT_EQ(io::parse_double(c.substr(0, sep), x), io::NumberStatus::Ok);
    ASSERT_EQ(io::parse_double(c.substr(sep + 1), y), io::NumberStatus::Ok);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(g.points[i].x), std::bit_cast<std::uint64_t>(x)) << c;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(g.points[i].y), std::bit_cast<std::uint64_t>(y)) << c;
    EXPECT_EQ(g.point_markers[i], i - 3);
  }
}

TEST_F(TextReaderFiles, ErrorsNameTheLineAsBefore) {
  const std::string head = "3 2 0 0\n0 0 0\n";
  EXPECT_EQ(node_error(head + "1 0.5 0.5e\n2 1 1\n"),
            "3: '0.5e' is not a number (expected the y coordinate of vertex 1)");
  EXPECT_EQ(node_error(head + "1 0x1p3 1\n2 1 1\n"),
            "3: '0x1p3' is not a number (expected the x coordinate of vertex 1)");
  EXPECT_EQ(node_error(head + "1 1e400 1\n2 1 1\n"),
            "3: '1e400' is out of range (expected the x coordinate of vertex 1)");
  EXPECT_EQ(node_error(head + "1 1 inf\n2 1 1\n"), "3: the y coordinate of vertex 1 is not finite ('inf')");
  EXPECT_EQ(node_error(head + "\r\n# gap\r\n2 1 1\n"),
            "5: vertex number 2 is out of order: vertices must be numbered consecutively, expected 1");
  EXPECT_EQ(node_error(head + "1 1 1\n"), "1: header announces 3 vertices but the file has only 2 lines left");
  EXPECT_EQ(node_error(head + "1 2\n2 1 1\n"), "3: expected 2 coordinates for vertex 1, found 1");
  // (Before the fast path checked the marker's range itself, this read
  // "1: header announces 2 vertices but the file ends after 1".)
  EXPECT_EQ(node_error("2 2 0 1\n0 0 0 1\n1 1 1 99999999999\n"),
            "3: boundary marker 99999999999 of vertex 1 does not fit in an int");
  EXPECT_EQ(node_error(head + "1 1 1\n2 0 1 # last\n3 5 5\n"),
            "5: unexpected data after the 3 vertices announced on line 1");
}

}  // namespace
