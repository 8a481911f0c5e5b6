// The strtod/snprintf fallback of src/core/float_chars.hpp (the web build's,
// compiled here natively) against std::from_chars / std::to_chars: the same
// values read, the same grammar refused, every double written reads back.
#define DELTAMESH_PORTABLE_FLOAT_CHARS 1
#include "core/float_chars.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace {

using namespace deltamesh;

struct Parsed {
  double value = -12345.0;
  std::size_t used = 0;
  std::errc ec{};
};

Parsed portable(const std::string& s) {
  Parsed p;
  const auto r = chars::portable::parse_double(s.data(), s.data() + s.size(), p.value);
  p.used = static_cast<std::size_t>(r.ptr - s.data());
  p.ec = r.ec;
  return p;
}

Parsed standard(const std::string& s) {
  Parsed p;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), p.value);
  p.used = static_cast<std::size_t>(r.ptr - s.data());
  p.ec = r.ec;
  return p;
}

TEST(FloatChars, ParsesAsFromChars) {
  for (const std::string s :
       {"0", "-0", "1", "1.5", "-2.25e-3", "1e308", "4.9e-324", "0.1", "123456789012345678901234567890", ".5", "5.",
        "1e", "1e+", "3.0 4", "7x", "0x10", "inf", "-infinity", "nan", "1.5e3.2", "--1", "-", "", "abc", " 1", "+1",
        "1e400", "-1e400", "2.2250738585072011e-308"}) {
    const Parsed a = portable(s), b = standard(s);
    EXPECT_EQ(a.ec, b.ec) << "'" << s << "'";
    if (b.ec == std::errc()) {
      EXPECT_EQ(a.used, b.used) << "'" << s << "'";
      if (std::isnan(b.value))
        EXPECT_TRUE(std::isnan(a.value)) << "'" << s << "'";
      else
        EXPECT_EQ(std::memcmp(&a.value, &b.value, sizeof(double)), 0) << "'" << s << "'";
    }
  }
}

TEST(FloatChars, ShortestReadsBack) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::uint64_t> bits;
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t u = bits(rng);
    double v;
    std::memcpy(&v, &u, sizeof v);
    if (!std::isfinite(v)) continue;
    char buf[64];
    const auto r = chars::portable::shortest(buf, buf + sizeof buf, v);
    ASSERT_EQ(r.ec, std::errc());
    double back = 0;
    const auto p = std::from_chars(buf, r.ptr, back);
    ASSERT_EQ(p.ptr, r.ptr) << std::string(buf, r.ptr);
    ASSERT_EQ(back, v) << std::string(buf, r.ptr);
    ++checked;
  }
  EXPECT_GT(checked, 19000);
  char buf[64];
  EXPECT_EQ(std::string(buf, chars::portable::shortest(buf, buf + sizeof buf, 0.1).ptr), "0.1");
  EXPECT_EQ(std::string(buf, chars::portable::shortest(buf, buf + sizeof buf, 30.0).ptr), "30");
  EXPECT_EQ(std::string(buf, chars::portable::fixed(buf, buf + sizeof buf, 2.345, 2).ptr), "2.35");
  EXPECT_EQ(std::string(buf, chars::portable::general(buf, buf + sizeof buf, 0.0123456, 3).ptr), "0.0123");
  // Too small a buffer is an error, not an overrun.
  EXPECT_EQ(chars::portable::shortest(buf, buf + 3, 1.0 / 3.0).ec, std::errc::value_too_large);
}

}  // namespace
