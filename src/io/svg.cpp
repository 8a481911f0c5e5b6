// SVG picture of a mesh.
//
// Layout: the mesh fills the picture width (less a margin) with the y axis
// pointing up, and a legend sits below it. Triangles are drawn as one <path>
// per fill colour (shade_by_quality groups them into 8 buckets of smallest
// angle), each stroked thinly so the edges show; constrained edges are drawn
// once more, bold, in their own path. Coordinates are rounded to a fixed
// grid (5 significant digits of the picture size) and written as relative
// moves, which keeps a 10^5-triangle picture to a few megabytes.
#include "deltamesh/svg.hpp"

#include <algorithm>
#include <array>
#include <charconv>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/angles.hpp"
#include "core/float_chars.hpp"
#include "deltamesh/version.hpp"
#include "deltamesh/voronoi.hpp"
#include "io/atomic_file.hpp"

namespace deltamesh {

namespace {


struct Bucket {
  double below;  // smallest angle (degrees) upper bound, exclusive
  const char* colour;
  const char* label;
};
constexpr std::array<Bucket, 8> kBuckets{{
    {10.0, "#8b0000", "&lt;10&#176;"},
    {20.0, "#e31a1c", "10-20&#176;"},
    {25.0, "#fd8d3c", "20-25&#176;"},
    {30.0, "#fecc5c", "25-30&#176;"},
    {35.0, "#d9ef8b", "30-35&#176;"},
    {40.0, "#a6d96a", "35-40&#176;"},
    {50.0, "#66bd63", "40-50&#176;"},
    {1e9, "#1a9850", "&#8805;50&#176;"},
}};
constexpr const char* kPlainFill = "#dbe4ee";

std::size_t bucket_of(double angle_deg) {
  std::size_t b = 0;
  while (b + 1 < kBuckets.size() && !(angle_deg < kBuckets[b].below)) ++b;
  return b;
}

std::string xml_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // Control characters are not allowed in XML 1.0 text.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          out += ' ';
        } else {
          out += c;
        }
    }
  }
  return out;
}

// Picture coordinates are integers in units of 10^-decimals pixels, so
// relative moves are exact differences.
class Grid {
 public:
  explicit Grid(int decimals) : decimals_(decimals), unit_(std::pow(10.0, decimals)) {}
  std::int64_t snap(double px) const { return std::llround(px * unit_); }
  // Appends v (in grid units) as a decimal number without trailing zeros
  // (and, in path data, without the leading zero of "0.5").
  void put(std::string& out, std::int64_t v, bool short_form = false) const {
    if (v < 0) {
      out += '-';
      v = -v;
    }
    char buf[32];
    std::int64_t scale = 1;
    for (int i = 0; i < decimals_; ++i) scale *= 10;
    const std::int64_t whole = v / scale;
    std::int64_t frac = v % scale;
    if (!(short_form && whole == 0 && frac != 0)) {
      char* e = std::to_chars(buf, buf + sizeof buf, whole).ptr;
      out.append(buf, e);
    }
    if (frac != 0) {
      int digits = decimals_;
      while (frac % 10 == 0) {
        frac /= 10;
        --digits;
      }
      out += '.';
      const std::string f = std::to_string(frac);
      out.append(static_cast<std::size_t>(digits) - f.size(), '0');
      out += f;
    }
  }
  // A number in a path: negative numbers separate themselves.
  void put_sep(std::string& out, std::int64_t v) const {
    if (v >= 0) out += ' ';
    put(out, v, true);
  }
  std::string text(double px) const {
    std::string s;
    put(s, snap(px));
    return s;
  }

 private:
  int decimals_;
  double unit_;
};

std::string fixed(double v, int decimals) {
  char buf[64];
  const auto r = chars::fixed(buf, buf + sizeof buf, v, decimals);
  return std::string(buf, r.ptr);
}

}  // namespace

void write_svg(const Mesh& mesh, const std::string& path, const SvgOptions& opt) {
  const std::size_t slots = mesh.num_triangle_slots();
  const auto pt = [&](VertexId v) -> const Point& { return mesh.point(v); };

  // Bounding box of the vertices of live triangles (of all vertices if none).
  double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
  std::vector<std::uint8_t> used(mesh.num_vertices(), 0);
  std::size_t num_tris = 0;
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    ++num_tris;
    for (const VertexId v : mesh.triangle(t)) used[v] = 1;
  }
  for (VertexId v = 0; v < mesh.num_vertices(); ++v) {
    if (num_tris > 0 && !used[v]) continue;
    const Point& p = pt(v);
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    minx = std::min(minx, p.x), maxx = std::max(maxx, p.x);
    miny = std::min(miny, p.y), maxy = std::max(maxy, p.y);
  }
  if (!(minx <= maxx)) minx = miny = 0.0, maxx = maxy = 1.0;

  // Scale: fill the width, but keep very tall meshes at most 4 widths high.
  const double width = std::isfinite(opt.width_px) && opt.width_px >= 50.0 ? opt.width_px : 800.0;
  const double margin = std::max(4.0, 0.02 * width);
  const double inner = width - 2.0 * margin;
  const double bw = maxx - minx, bh = maxy - miny;
  double scale = bw > 0.0 ? inner / bw : (bh > 0.0 ? inner / bh : 1.0);
  if (bh * scale > 4.0 * inner) scale = 4.0 * inner / bh;
  const double draw_h = bh * scale;
  const double ox = margin + (inner - bw * scale) / 2.0;
  const double font = 12.0;
  const double legend_h = opt.shade_by_quality ? 3.2 * font : 2.0 * font;
  const double height = std::ceil(draw_h + 2.0 * margin + legend_h);
  const int decimals = std::clamp(5 - static_cast<int>(std::ceil(std::log10(std::max(width, height)))), 0, 3);
  const Grid grid(decimals);
  const auto X = [&](const Point& p) { return grid.snap(ox + (p.x - minx) * scale); };
  const auto Y = [&](const Point& p) { return grid.snap(margin + (maxy - p.y) * scale); };

  // Triangles by bucket, and the smallest angle overall.
  const std::size_t nb = opt.shade_by_quality ? kBuckets.size() : 1;
  std::vector<std::string> paths(nb);
  std::vector<std::size_t> counts(nb, 0);
  std::vector<std::array<std::int64_t, 2>> last(nb, {0, 0});  // previous subpath start
  double min_angle = 180.0;
  double edge_px_sum = 0.0;
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    const auto tri = mesh.triangle(t);
    const Point &a = pt(tri[0]), &b = pt(tri[1]), &c = pt(tri[2]);
    const double angle = smallest_angle_deg(a, b, c);
    min_angle = std::min(min_angle, angle);
    edge_px_sum += std::hypot(b.x - a.x, b.y - a.y) * scale;
    const std::size_t k = opt.shade_by_quality ? bucket_of(angle) : 0;
    ++counts[k];
    std::string& d = paths[k];
    const std::int64_t ax = X(a), ay = Y(a), bx = X(b), by = Y(b), cx = X(c), cy = Y(c);
    const bool first = d.empty();
    d += first ? 'M' : 'm';
    const std::int64_t mx = first ? ax : ax - last[k][0];
    const std::int64_t my = first ? ay : ay - last[k][1];
    grid.put(d, mx, true);
    grid.put_sep(d, my);
    d += 'l';
    grid.put(d, bx - ax, true);
    grid.put_sep(d, by - ay);
    grid.put_sep(d, cx - bx);
    grid.put_sep(d, cy - by);
    d += 'z';
    last[k] = {ax, ay};
  }
  if (num_tris == 0) min_angle = 0.0;

  // Stroke widths follow the typical edge length so dense meshes stay legible.
  const double mean_edge = num_tris > 0 ? edge_px_sum / static_cast<double>(num_tris) : 10.0;
  const double thin = std::clamp(0.06 * mean_edge, 0.05, 0.8);
  const double bold = std::clamp(3.0 * thin, 0.6, 2.4);

  // Constrained edges, each once.
  std::string seg;
  std::size_t num_segments = 0;
  if (mesh.has_edge_flags()) {
    std::int64_t px = 0, py = 0;
    for (TriId t = 0; t < slots; ++t) {
      if (!mesh.is_real(t)) continue;
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        HalfEdgeId tw = mesh.twin(e);
        if (tw != kNone && !mesh.is_real(tri_of(tw))) tw = kNone;
        if (tw != kNone && tw < e) continue;
        if (!mesh.is_constrained(e) && !(tw != kNone && mesh.is_constrained(tw))) continue;
        const Point &p = pt(mesh.origin(e)), &q = pt(mesh.dest(e));
        const std::int64_t x0 = X(p), y0 = Y(p), x1 = X(q), y1 = Y(q);
        const bool first = seg.empty();
        seg += first ? 'M' : 'm';
        grid.put(seg, first ? x0 : x0 - px, true);
        grid.put_sep(seg, first ? y0 : y0 - py);
        seg += 'l';
        grid.put(seg, x1 - x0, true);
        grid.put_sep(seg, y1 - y0);
        px = x1, py = y1;
        ++num_segments;
      }
    }
  }

  std::string out;
  std::size_t total = 4096 + seg.size();
  for (const std::string& d : paths) total += d.size() + 128;
  out.reserve(total);
  const std::string w = fixed(width, 0), h = fixed(height, 0);
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + w + "\" height=\"" + h +
         "\" viewBox=\"0 0 " + w + " " + h + "\">\n";
  const std::string title = opt.title.empty() ? std::string("deltamesh mesh") : opt.title;
  out += "<title>" + xml_escape(title) + "</title>\n";
  out += "<desc>Generated by deltamesh " + std::string(kVersion) + ": " + std::to_string(mesh.num_vertices()) +
         " vertices, " + std::to_string(num_tris) + " triangles</desc>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"" + w + "\" height=\"" + h + "\" fill=\"#ffffff\"/>\n";
  out += "<g stroke=\"#2b2b2b\" stroke-width=\"" + fixed(thin, 3) + "\" stroke-linejoin=\"round\">\n";
  for (std::size_t k = 0; k < nb; ++k) {
    if (paths[k].empty()) continue;
    out += "<path class=\"tri\" fill=\"";
    out += opt.shade_by_quality ? kBuckets[k].colour : kPlainFill;
    out += "\" d=\"";
    out += paths[k];
    out += "\"/>\n";
  }
  out += "</g>\n";
  if (!seg.empty())
    out += "<path class=\"segments\" fill=\"none\" stroke=\"#000000\" stroke-width=\"" + fixed(bold, 3) +
           "\" stroke-linecap=\"round\" d=\"" + seg + "\"/>\n";
  if (opt.voronoi) {
    // Voronoi overlay: each cell as a closed subpath (relative moves).
    std::string d;
    std::int64_t px = 0, py = 0;
    for (const VoronoiCell& cell : opt.voronoi->cells) {
      if (cell.ring.size() < 3) continue;
      const bool first = d.empty();
      const std::int64_t x0 = X(cell.ring[0]), y0 = Y(cell.ring[0]);
      d += first ? 'M' : 'm';
      grid.put(d, first ? x0 : x0 - px, true);
      grid.put_sep(d, first ? y0 : y0 - py);
      d += 'l';
      std::int64_t cx = x0, cy = y0;
      for (std::size_t i = 1; i < cell.ring.size(); ++i) {
        const std::int64_t x = X(cell.ring[i]), y = Y(cell.ring[i]);
        grid.put_sep(d, x - cx);
        grid.put_sep(d, y - cy);
        cx = x, cy = y;
      }
      d += 'z';
      px = x0, py = y0;
    }
    if (!d.empty())
      out += "<path class=\"voronoi\" fill=\"none\" stroke=\"#1f5fbf\" stroke-width=\"" + fixed(thin, 3) +
             "\" stroke-linejoin=\"round\" d=\"" + d + "\"/>\n";
  }
  if (opt.draw_vertices) {
    const std::string r = fixed(std::clamp(2.0 * thin, 0.4, 2.5), 3);
    out += "<g class=\"vertices\" fill=\"#1f3a93\">\n";
    for (VertexId v = 0; v < mesh.num_vertices(); ++v) {
      if (num_tris > 0 && !used[v]) continue;
      const Point& p = pt(v);
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
      out += "<circle cx=\"";
      grid.put(out, X(p));
      out += "\" cy=\"";
      grid.put(out, Y(p));
      out += "\" r=\"" + r + "\"/>\n";
    }
    out += "</g>\n";
  }

  // Legend.
  const double ly = draw_h + 2.0 * margin + font;
  out += "<g font-family=\"sans-serif\" font-size=\"" + fixed(font, 0) + "\" fill=\"#000000\">\n";
  out += "<text x=\"" + grid.text(margin) + "\" y=\"" + grid.text(ly) + "\">" +
         std::to_string(mesh.num_vertices()) + " vertices, " + std::to_string(num_tris) + " triangles";
  if (num_segments > 0) out += ", " + std::to_string(num_segments) + " segment edges";
  if (num_tris == 0) {
    out += ", min angle n/a";
  } else {
    // Two decimals, or three significant digits for tiny angles.
    char buf[32];
    const auto r = min_angle >= 0.1 || min_angle == 0.0
                       ? chars::fixed(buf, buf + sizeof buf, min_angle, 2)
                       : chars::general(buf, buf + sizeof buf, min_angle, 3);
    out += ", min angle " + std::string(buf, r.ptr) + "&#176;";
  }
  out += "</text>\n";
  if (opt.shade_by_quality) {
    const double step = (width - 2.0 * margin) / static_cast<double>(kBuckets.size());
    const double sy = ly + 0.6 * font;
    for (std::size_t k = 0; k < kBuckets.size(); ++k) {
      const double x = margin + step * static_cast<double>(k);
      out += "<rect x=\"" + grid.text(x) + "\" y=\"" + grid.text(sy) + "\" width=\"" + grid.text(font) +
             "\" height=\"" + grid.text(font) + "\" fill=\"" + kBuckets[k].colour +
             "\" stroke=\"#2b2b2b\" stroke-width=\"0.5\"/>";
      out += "<text x=\"" + grid.text(x + 1.3 * font) + "\" y=\"" + grid.text(sy + 0.85 * font) +
             "\" font-size=\"" + fixed(0.8 * font, 1) + "\">" + kBuckets[k].label + ": " +
             std::to_string(counts[k]) + "</text>\n";
    }
  }
  out += "</g>\n</svg>\n";

  io::AtomicFile file(path);
  file.write(out);
  file.commit();
}

}  // namespace deltamesh
