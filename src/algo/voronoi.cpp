// Voronoi diagram from a triangulation: the dual graph (circumcentres and
// dual edges) and bounded cells clipped to the domain (see voronoi.hpp for
// what is computed on non-convex domains).
#include "deltamesh/voronoi.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "deltamesh/predicates.hpp"
#include "mesh/edge_rules.hpp"

namespace deltamesh {

namespace {

Point circumcentre(const Point& a, const Point& b, const Point& c) {
  const double bx = b.x - a.x, by = b.y - a.y;
  const double cx = c.x - a.x, cy = c.y - a.y;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double d = 2.0 * (bx * cy - by * cx);
  return {a.x + (cy * b2 - by * c2) / d, a.y + (bx * c2 - cx * b2) / d};
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// ---------------------------------------------------------------------------
// Convex polygon clipping

using Polygon = std::vector<Point>;

// Keeps the part of convex polygon `poly` where f(x) = nx*x + ny*y - c <= 0.
void clip(Polygon& poly, double nx, double ny, double c, Polygon& scratch) {
  const std::size_t n = poly.size();
  if (n == 0) return;
  scratch.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % n];
    const double fp = nx * p.x + ny * p.y - c;
    const double fq = nx * q.x + ny * q.y - c;
    if (fp <= 0.0) scratch.push_back(p);
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
      const double t = fp / (fp - fq);
      scratch.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
    }
  }
  poly.swap(scratch);
}

// Keeps the points at least as close to v as to u.
void clip_bisector(Polygon& poly, const Point& v, const Point& u, Polygon& scratch) {
  const double nx = u.x - v.x, ny = u.y - v.y;
  const double mx = 0.5 * (u.x + v.x), my = 0.5 * (u.y + v.y);
  clip(poly, nx, ny, nx * mx + ny * my, scratch);
}

// Keeps the points on the left of the directed line a -> b (right when `left` is false).
void clip_line(Polygon& poly, const Point& a, const Point& b, bool left, Polygon& scratch) {
  // left: cross(b - a, x - a) >= 0  <=>  -(b-a).y * x + (b-a).x * y ... written as f <= 0.
  double nx = (b.y - a.y), ny = -(b.x - a.x);  // f = n.(x - a) = -cross(b - a, x - a)
  if (!left) nx = -nx, ny = -ny;
  clip(poly, nx, ny, nx * a.x + ny * a.y, scratch);
}

// Parameter range [t0, t1] of segment p + t (q - p), t in [0, 1], inside the
// convex counter-clockwise polygon (Cyrus-Beck). Empty when t0 > t1.
void segment_range(const Polygon& poly, const Point& p, const Point& q, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const std::size_t n = poly.size();
  if (n < 3) {
    t0 = 1.0, t1 = 0.0;
    return;
  }
  const double dx = q.x - p.x, dy = q.y - p.y;
  for (std::size_t i = 0; i < n && t0 <= t1; ++i) {
    const Point& a = poly[i];
    const Point& b = poly[(i + 1) % n];
    // Inside: cross(b - a, x - a) >= 0.
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double f0 = cross(ex, ey, p.x - a.x, p.y - a.y);
    const double df = cross(ex, ey, dx, dy);
    if (df == 0.0) {
      if (f0 < 0.0) t0 = 1.0, t1 = 0.0;
      continue;
    }
    const double t = -f0 / df;
    if (df > 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
}

double ring_area(const Polygon& poly) {
  double a = 0.0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point& p = poly[i];
    const Point& q = poly[(i + 1) % n];
    a += p.x * q.y - p.y * q.x;
  }
  return 0.5 * a;
}

// Drops consecutive points closer than `tol` (clipping leaves such pairs
// where a cut passes through a vertex).
void dedupe(Polygon& poly, double tol) {
  Polygon out;
  for (const Point& p : poly)
    if (out.empty() || std::fabs(p.x - out.back().x) > tol || std::fabs(p.y - out.back().y) > tol) out.push_back(p);
  while (out.size() > 1 && std::fabs(out.front().x - out.back().x) <= tol &&
         std::fabs(out.front().y - out.back().y) <= tol)
    out.pop_back();
  poly.swap(out);
}

// Where the ray v + s d (s > 0) leaves convex polygon `poly` (v inside):
// the point and the index of the edge it crosses.
bool ray_exit(const Polygon& poly, const Point& v, double dx, double dy, Point& hit, std::size_t& edge) {
  const std::size_t n = poly.size();
  double best_err = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const Point& a = poly[i];
    const Point& b = poly[(i + 1) % n];
    const double ex = b.x - a.x, ey = b.y - a.y;
    const double den = cross(dx, dy, ex, ey);
    if (den == 0.0) continue;
    const double s = cross(a.x - v.x, a.y - v.y, ex, ey) / den;
    const double t = cross(a.x - v.x, a.y - v.y, dx, dy) / den;
    if (!(s > 0.0)) continue;
    const double err = t < 0.0 ? -t : (t > 1.0 ? t - 1.0 : 0.0);
    if (err < best_err) {
      best_err = err;
      edge = i;
      hit = {v.x + s * dx, v.y + s * dy};
    }
  }
  return best_err < 1e-6;
}

}  // namespace

// ---------------------------------------------------------------------------

VoronoiDiagram voronoi_diagram(const Mesh& mesh) {
  VoronoiDiagram d;
  const std::size_t slots = mesh.num_triangle_slots();
  std::vector<std::uint32_t> index(slots, kNone);
  const std::size_t na = mesh.num_vertex_attributes();
  const std::vector<double>& attr = mesh.vertex_attributes();
  d.num_attributes = na;
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    index[t] = static_cast<std::uint32_t>(d.vertices.size());
    const auto v = mesh.triangle(t);
    const Point &a = mesh.point(v[0]), &b = mesh.point(v[1]), &c = mesh.point(v[2]);
    const Point cc = circumcentre(a, b, c);
    d.vertices.push_back(cc);
    if (na == 0) continue;
    // Barycentric coordinates of the circumcentre (1 - xi - eta, xi, eta).
    const double det = cross(b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y);
    const double xi = cross(cc.x - a.x, cc.y - a.y, c.x - a.x, c.y - a.y) / det;
    const double eta = cross(b.x - a.x, b.y - a.y, cc.x - a.x, cc.y - a.y) / det;
    for (std::size_t k = 0; k < na; ++k) {
      const auto at = [&](VertexId u) {
        const std::size_t i = std::size_t{u} * na + k;
        return i < attr.size() ? attr[i] : 0.0;
      };
      const double fa = at(v[0]);
      d.attributes.push_back(fa + xi * (at(v[1]) - fa) + eta * (at(v[2]) - fa));
    }
  }
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
      const HalfEdgeId tw = real_twin(mesh, e);
      if (tw != kNone && tw < e) continue;
      VoronoiDiagram::Edge edge;
      edge.a = index[t];
      edge.delaunay_edge = e;
      if (tw != kNone) {
        edge.b = index[tri_of(tw)];
      } else {
        // The triangle is on the left of p -> q; outward is to the right.
        const Point& p = mesh.point(mesh.origin(e));
        const Point& q = mesh.point(mesh.dest(e));
        edge.direction = {q.y - p.y, -(q.x - p.x)};
      }
      d.edges.push_back(edge);
    }
  }
  return d;
}

BoundedVoronoi bounded_voronoi(const Mesh& mesh) {
  BoundedVoronoi out;
  const std::size_t nv = mesh.num_vertices();
  const std::size_t slots = mesh.num_triangle_slots();

  // A box around every used vertex, far enough out to hold every cell's
  // part inside the domain (cells are clipped to the domain afterwards).
  double minx = INFINITY, miny = INFINITY, maxx = -INFINITY, maxy = -INFINITY;
  std::vector<TriId> first_tri(nv, kNone);
  for (TriId t = 0; t < slots; ++t) {
    if (!mesh.is_real(t)) continue;
    for (const VertexId v : mesh.triangle(t)) {
      if (first_tri[v] == kNone) first_tri[v] = t;
      const Point& p = mesh.point(v);
      minx = std::min(minx, p.x), maxx = std::max(maxx, p.x);
      miny = std::min(miny, p.y), maxy = std::max(maxy, p.y);
    }
  }
  if (!(minx <= maxx)) return out;
  const double size = std::max(maxx - minx, maxy - miny);
  const double pad = std::max(size, 1e-300);
  const double tol = 1e-13 * std::max({size, std::fabs(minx), std::fabs(maxx), std::fabs(miny), std::fabs(maxy)});
  const Polygon box{{minx - pad, miny - pad}, {maxx + pad, miny - pad}, {maxx + pad, maxy + pad}, {minx - pad, maxy + pad}};

  std::vector<std::uint32_t> tri_stamp(slots, 0), vert_stamp(nv, 0);
  std::vector<TriId> queue;
  std::vector<HalfEdgeId> boundary;
  Polygon poly, scratch;

  for (VertexId v = 0; v < nv; ++v) {
    if (first_tri[v] == kNone) continue;
    const std::uint32_t stamp = v + 1;
    const Point& pv = mesh.point(v);
    poly = box;
    vert_stamp[v] = stamp;
    boundary.clear();
    queue.clear();

    // Visits triangle t: bisectors with its vertices, its boundary edges.
    const auto visit = [&](TriId t) {
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        const VertexId u = mesh.origin(e);
        if (vert_stamp[u] != stamp) {
          vert_stamp[u] = stamp;
          clip_bisector(poly, pv, mesh.point(u), scratch);
        }
        if (real_twin(mesh, e) == kNone) boundary.push_back(e);
      }
    };

    // 1. The triangles around v (across edges incident to v).
    tri_stamp[first_tri[v]] = stamp;
    queue.push_back(first_tri[v]);
    for (std::size_t i = 0; i < queue.size(); ++i) {
      const TriId t = queue[i];
      visit(t);
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        if (mesh.origin(e) != v && mesh.dest(e) != v) continue;
        const HalfEdgeId tw = real_twin(mesh, e);
        if (tw == kNone || tri_stamp[tri_of(tw)] == stamp) continue;
        tri_stamp[tri_of(tw)] = stamp;
        queue.push_back(tri_of(tw));
      }
    }
    // 2. Onwards, across edges the cell still overlaps.
    const std::size_t star = queue.size();
    for (std::size_t i = 0; i < queue.size(); ++i) {
      const TriId t = queue[i];
      if (i >= star) visit(t);
      for (HalfEdgeId e = 3 * t; e < 3 * t + 3; ++e) {
        const HalfEdgeId tw = real_twin(mesh, e);
        if (tw == kNone || tri_stamp[tri_of(tw)] == stamp) continue;
        double t0, t1;
        segment_range(poly, mesh.point(mesh.origin(e)), mesh.point(mesh.dest(e)), t0, t1);
        if (t0 > t1) continue;
        tri_stamp[tri_of(tw)] = stamp;
        queue.push_back(tri_of(tw));
      }
    }

    // 3. Boundary edges not at v cut the cell on v's side.
    HalfEdgeId e_out = kNone;
    for (const HalfEdgeId e : boundary) {
      const VertexId a = mesh.origin(e), b = mesh.dest(e);
      if (a == v) {
        if (e_out == kNone) e_out = e;
        continue;
      }
      if (b == v) continue;
      const Point &pa = mesh.point(a), &pb = mesh.point(b);
      double t0, t1;
      segment_range(poly, pa, pb, t0, t1);
      if (!(t0 < t1)) continue;
      const double side = orient2d(pa, pb, pv);
      clip_line(poly, pa, pb, side >= 0.0, scratch);
    }

    // 4. At a boundary vertex, the domain's wedge between its two boundary
    // edges (the fan of the first outgoing boundary edge found).
    if (e_out != kNone && poly.size() >= 3) {
      HalfEdgeId e = e_out;
      for (std::size_t guard = 0; guard < slots + 1; ++guard) {
        const HalfEdgeId r = real_twin(mesh, prev_edge(e));
        if (r == kNone) break;
        e = r;
      }
      const HalfEdgeId e_in = prev_edge(e);  // u -> v
      const Point& pu = mesh.point(mesh.origin(e_in));
      const Point& pw = mesh.point(mesh.dest(e_out));
      if (orient2d(pu, pv, pw) >= 0.0) {
        clip_line(poly, pu, pv, true, scratch);
        clip_line(poly, pv, pw, true, scratch);
      } else {
        // Reflex corner: remove the outside wedge, counter-clockwise from
        // the direction of u to the direction of w.
        Point a_hit, b_hit;
        std::size_t ia = 0, ib = 0;
        if (ray_exit(poly, pv, pu.x - pv.x, pu.y - pv.y, a_hit, ia) &&
            ray_exit(poly, pv, pw.x - pv.x, pw.y - pv.y, b_hit, ib)) {
          const std::size_t n = poly.size();
          scratch.clear();
          scratch.push_back(b_hit);
          std::size_t k = (ib + 1) % n;
          for (std::size_t guard = 0; guard < n; ++guard) {
            scratch.push_back(poly[k]);
            if (k == ia) break;
            k = (k + 1) % n;
          }
          scratch.push_back(a_hit);
          scratch.push_back(pv);
          poly.swap(scratch);
        }
      }
    }

    dedupe(poly, tol);
    if (poly.size() < 3) continue;
    VoronoiCell cell;
    cell.site = v;
    cell.area = ring_area(poly);
    if (cell.area < 0.0) {
      std::reverse(poly.begin(), poly.end());
      cell.area = -cell.area;
    }
    cell.ring = poly;
    out.cells.push_back(std::move(cell));
  }
  return out;
}

}  // namespace deltamesh
