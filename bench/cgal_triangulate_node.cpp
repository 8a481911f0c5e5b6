// cgal_triangulate_node: the whole-process CGAL peer of `deltamesh -NQ`.
// Reads a Triangle .node file, builds CGAL::Delaunay_triangulation_2 with
// the exact-predicates inexact-constructions kernel by range insert (which
// sorts spatially first) and writes the triangles as an .ele file numbered
// like the input. Input is read whole and parsed with std::from_chars;
// output is assembled with std::to_chars and written at once, so I/O is as
// lean as ours.
//
// usage: cgal_triangulate_node [--no-output] [-o FILE] [-v] FILE.node
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Dt = CGAL::Delaunay_triangulation_2<K, Tds>;

[[noreturn]] void fail(const std::string& msg) {
  std::fprintf(stderr, "cgal_triangulate_node: %s\n", msg.c_str());
  std::exit(1);
}

bool read_file(const char* path, std::string& out) {
  std::FILE* f = std::fopen(path, "rb");
  if (!f) return false;
  std::fseek(f, 0, SEEK_END);
  const long size = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  out.resize(size > 0 ? static_cast<std::size_t>(size) : 0);
  const bool ok = std::fread(out.data(), 1, out.size(), f) == out.size();
  std::fclose(f);
  return ok;
}

// Tokenizer over the whole file: whitespace separated, '#' to end of line is a comment.
class Scanner {
 public:
  explicit Scanner(const std::string& s) : p_(s.data()), end_(s.data() + s.size()) {}
  std::size_t line() const { return line_; }
  // Skips blanks and comments; stops at a newline when stop_at_eol.
  void skip(bool stop_at_eol) {
    while (p_ < end_) {
      if (*p_ == '#') {
        while (p_ < end_ && *p_ != '\n') ++p_;
      } else if (*p_ == '\n') {
        if (stop_at_eol) return;
        ++line_;
        ++p_;
      } else if (*p_ == ' ' || *p_ == '\t' || *p_ == '\r') {
        ++p_;
      } else {
        return;
      }
    }
  }
  template <class T>
  T number() {
    skip(false);
    T v{};
    const auto r = std::from_chars(p_, end_, v);
    if (r.ec != std::errc()) fail("line " + std::to_string(line_) + ": number expected");
    p_ = r.ptr;
    return v;
  }
  // Drops the rest of the current line (attributes, markers).
  void next_line() {
    while (p_ < end_ && *p_ != '\n') ++p_;
  }

 private:
  const char* p_;
  const char* end_;
  std::size_t line_ = 1;
};

class Writer {
 public:
  void reserve(std::size_t n) { buf_.reserve(n); }
  void integer(std::uint64_t v, char sep) {
    char tmp[24];
    char* e = std::to_chars(tmp, tmp + sizeof tmp, v).ptr;
    *e++ = sep;
    buf_.append(tmp, e);
  }
  void text(std::string_view s) { buf_.append(s); }
  bool save(const std::string& path) const {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return false;
    const bool ok = std::fwrite(buf_.data(), 1, buf_.size(), f) == buf_.size();
    return std::fclose(f) == 0 && ok;
  }

 private:
  std::string buf_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  bool output = true, verbose = false;
  std::string in_path, out_path;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--no-output") {
      output = false;
    } else if (a == "-v") {
      verbose = true;
    } else if (a == "-o" && i + 1 < argc) {
      out_path = argv[++i];
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "usage: cgal_triangulate_node [--no-output] [-o FILE] [-v] FILE.node\n"
          "Delaunay triangulation of a .node file with CGAL (Epick, range insert);\n"
          "writes FILE.1.ele (or -o FILE), numbered like the input.\n"
          "  --no-output  triangulate only\n"
          "  -v           print phase times to stderr\n");
      return 0;
    } else if (!a.empty() && a[0] != '-' && in_path.empty()) {
      in_path = a;
    } else {
      fail("bad argument '" + std::string(a) + "' (try --help)");
    }
  }
  if (in_path.empty()) fail("no input file (try --help)");
  if (out_path.empty()) {
    const auto dot = in_path.rfind(".node");
    out_path = (dot == std::string::npos ? in_path : in_path.substr(0, dot)) + ".1.ele";
  }

  const auto t0 = std::chrono::steady_clock::now();
  std::string text;
  if (!read_file(in_path.c_str(), text)) fail("cannot read " + in_path);
  Scanner in(text);
  const auto n = in.number<std::uint64_t>();
  const auto dim = in.number<int>();
  in.next_line();
  if (dim != 2) fail("only 2-dimensional .node files");
  if (n >= 0xffffffffu) fail("too many points");
  std::vector<std::pair<K::Point_2, std::uint32_t>> pts;
  pts.reserve(n);
  std::uint64_t first_index = 0;
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto id = in.number<std::uint64_t>();
    if (i == 0) first_index = id;
    const auto x = in.number<double>();
    const auto y = in.number<double>();
    in.next_line();
    pts.emplace_back(K::Point_2(x, y), static_cast<std::uint32_t>(i));
  }
  const double t_read = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  Dt dt;
  dt.insert(pts.begin(), pts.end());
  const double t_tri = seconds_since(t1);

  const auto t2 = std::chrono::steady_clock::now();
  if (output) {
    Writer w;
    w.reserve(dt.number_of_faces() * 32 + 32);
    w.integer(dt.number_of_faces(), ' ');
    w.text("3 0\n");
    std::uint64_t t = 0;
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
      w.integer(t++ + first_index, ' ');
      w.integer(f->vertex(0)->info() + first_index, ' ');
      w.integer(f->vertex(1)->info() + first_index, ' ');
      w.integer(f->vertex(2)->info() + first_index, '\n');
    }
    if (!w.save(out_path)) fail("cannot write " + out_path);
  }
  const double t_write = seconds_since(t2);
  if (verbose)
    std::fprintf(stderr, "%llu points, %zu triangles; read %.3f s, triangulate %.3f s, write %.3f s\n",
                 static_cast<unsigned long long>(n), static_cast<std::size_t>(dt.number_of_faces()), t_read,
                 t_tri, t_write);
  return 0;
}
