// deltamesh-gen: writes seeded test inputs as Triangle .node / .poly files.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <system_error>

#include "generators.hpp"

namespace {

using namespace deltamesh;

void print_help(std::FILE* out) {
  std::fprintf(out,
               "usage: deltamesh-gen KIND N [--seed S] [--scale F] [--poly] [-o FILE]\n"
               "\n"
               "Writes a seeded input as a Triangle .node file (0-based; smooth from 1) to\n"
               "stdout or FILE.\n"
               "The same KIND, N, seed and scale always give the same bytes.\n"
               "\n"
               "KIND:\n");
  for (const gen::KindInfo& k : gen::kKinds)
    std::fprintf(out, "  %-12.*s %.*s\n", static_cast<int>(k.name.size()), k.name.data(),
                 static_cast<int>(k.help.size()), k.help.data());
  std::fprintf(out,
               "\n"
               "options:\n"
               "  --seed S    seed of the generator (default 1)\n"
               "  --scale F   multiply every coordinate by F (default 1)\n"
               "  --poly      write a .poly file (points, then 0 segments and 0 holes);\n"
               "              always on for star, square-hole and smooth\n"
               "  -o FILE     write to FILE instead of stdout\n"
               "  -h, --help  this text\n"
               "N may be written as 1000000 or 1e6; for smooth it defaults to 100000.\n");
}

[[noreturn]] void fail(const std::string& msg) {
  std::fprintf(stderr, "deltamesh-gen: %s (try --help)\n", msg.c_str());
  std::exit(2);
}

bool parse_double(std::string_view s, double& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(out);
}

// A count: an integer, possibly in exponent form (1e6).
bool parse_count(std::string_view s, std::size_t& out) {
  std::uint64_t u = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), u);
  if (r.ec == std::errc() && r.ptr == s.data() + s.size()) {
    out = u;
    return true;
  }
  double d = 0.0;
  if (!parse_double(s, d) || d < 0.0 || d > 0x1p32 || d != std::floor(d)) return false;
  out = static_cast<std::size_t>(d);
  return true;
}

// Output assembled in memory, written with one fwrite.
class Writer {
 public:
  void text(std::string_view s) { buf_.append(s); }
  void integer(std::uint64_t v) {
    char tmp[24];
    buf_.append(tmp, std::to_chars(tmp, tmp + sizeof tmp, v).ptr);
  }
  void real(double v) {
    char tmp[32];
    buf_.append(tmp, std::to_chars(tmp, tmp + sizeof tmp, v).ptr);  // shortest round trip
  }
  void point_line(std::uint64_t i, const Point& p) {  // i: as numbered in the file
    integer(i);
    text(" ");
    real(p.x);
    text(" ");
    real(p.y);
    text("\n");
  }
  void reserve(std::size_t n) { buf_.reserve(n); }
  bool flush(std::FILE* f) const { return std::fwrite(buf_.data(), 1, buf_.size(), f) == buf_.size(); }

 private:
  std::string buf_;
};

// Vertices, segments and holes numbered from g.first_index.
void write(const Pslg& g, bool poly, Writer& w) {
  const auto base = static_cast<std::uint64_t>(g.first_index);
  w.reserve(g.points.size() * 48 + g.segments.size() * 24 + 64);
  w.integer(g.points.size());
  w.text(" 2 0 0\n");
  for (std::size_t i = 0; i < g.points.size(); ++i) w.point_line(base + i, g.points[i]);
  if (!poly) return;
  w.integer(g.segments.size());
  w.text(" 0\n");
  for (std::size_t i = 0; i < g.segments.size(); ++i) {
    w.integer(base + i);
    w.text(" ");
    w.integer(base + g.segments[i].a);
    w.text(" ");
    w.integer(base + g.segments[i].b);
    w.text("\n");
  }
  w.integer(g.holes.size());
  w.text("\n");
  for (std::size_t i = 0; i < g.holes.size(); ++i) w.point_line(base + i, g.holes[i]);
}

}  // namespace

int main(int argc, char** argv) {
  std::string_view positional[2];
  int npos = 0;
  std::uint64_t seed = 1;
  double scale = 1.0;
  bool poly = false;
  const char* out_path = nullptr;

  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) fail("option " + std::string(a) + " needs a value");
      return argv[++i];
    };
    if (a == "-h" || a == "--help") {
      print_help(stdout);
      return 0;
    } else if (a == "--seed") {
      const std::string_view v = value();
      const auto r = std::from_chars(v.data(), v.data() + v.size(), seed);
      if (r.ec != std::errc() || r.ptr != v.data() + v.size()) fail("bad seed '" + std::string(v) + "'");
    } else if (a == "--scale") {
      const std::string_view v = value();
      if (!parse_double(v, scale) || scale == 0.0) fail("bad scale '" + std::string(v) + "'");
    } else if (a == "--poly") {
      poly = true;
    } else if (a == "-o") {
      out_path = value().data();
    } else if (a.size() > 1 && a[0] == '-') {
      fail("unknown option '" + std::string(a) + "'");
    } else {
      if (npos == 2) fail("too many arguments");
      positional[npos++] = a;
    }
  }
  if (npos < 1) {
    print_help(stderr);
    return 2;
  }
  const auto kind = gen::parse_kind(positional[0]);
  if (!kind) fail("unknown kind '" + std::string(positional[0]) + "'");
  // N is required except for smooth, whose benchmark size is the default.
  if (npos < 2 && *kind != gen::Kind::Smooth) {
    print_help(stderr);
    return 2;
  }
  std::size_t n = 100000;
  if (npos == 2 && !parse_count(positional[1], n)) fail("bad count '" + std::string(positional[1]) + "'");
  if ((*kind == gen::Kind::Star || *kind == gen::Kind::Smooth) && n < 3)
    fail(std::string(positional[0]) + " needs N >= 3");
  if (gen::is_polygon_kind(*kind)) poly = true;

  const Pslg g = gen::generate(*kind, n, seed, scale);
  Writer w;
  write(g, poly, w);

  std::FILE* f = stdout;
  if (out_path) {
    f = std::fopen(out_path, "wb");
    if (!f) fail(std::string("cannot open ") + out_path + ": " + std::strerror(errno));
  }
  const bool ok = w.flush(f) && std::fflush(f) == 0;
  if (out_path && std::fclose(f) != 0) {
    std::fprintf(stderr, "deltamesh-gen: cannot write %s\n", out_path);
    return 1;
  }
  if (!ok) {
    std::fprintf(stderr, "deltamesh-gen: write failed\n");
    return 1;
  }
  return 0;
}
