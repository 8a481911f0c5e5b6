// Robust predicates against exact GMP oracles: 10^6 seeded near-degenerate
// cases per predicate, classic adversarial sets, symmetry properties and the
// input range check.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/predicates.hpp"
#include "support/gmp_oracle.hpp"

using deltamesh::Point;
using deltamesh::oracle::GmpOracle;
using deltamesh::oracle::sign_of;

namespace {

constexpr int kRandomCases = 1'000'000;

bool coord_ok(double v) {
  const double m = std::fabs(v);
  return m <= deltamesh::kMaxCoordinate && (m == 0.0 || m >= deltamesh::kMinCoordinate);
}
bool point_ok(const Point& p) { return coord_ok(p.x) && coord_ok(p.y); }
bool weight_ok(double w) {
  const double m = std::fabs(w);
  return m <= deltamesh::kMaxWeight && (m == 0.0 || m >= deltamesh::kMinWeight);
}

// v moved by k ulps (k < 0: downwards).
double ulps(double v, int k) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (; k > 0; --k) v = std::nextafter(v, inf);
  for (; k < 0; ++k) v = std::nextafter(v, -inf);
  return v;
}

std::string str(const Point& p) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << p.x << ", " << p.y << ")";
  return os.str();
}

// Seeded generator of near-degenerate inputs at many magnitudes.
class Gen {
 public:
  explicit Gen(std::uint64_t seed) : rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int irange(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  bool coin(double p = 0.5) { return uniform(0.0, 1.0) < p; }
  std::mt19937_64& rng() { return rng_; }

  // A length scale: unit, moderate (1e-9..1e9), huge (1e25..1e59), tiny
  // (1e-35..1e-25), anywhere in range, or right at the range limits.
  double scale() {
    switch (irange(0, 9)) {
      case 0:
      case 1:
        return 1.0;
      case 2:
      case 3:
        return std::pow(10.0, uniform(-9.0, 9.0));
      case 4:
        return std::pow(10.0, uniform(25.0, 59.0));
      case 5:
        return std::pow(10.0, uniform(-35.0, -25.0));
      case 6:
        return std::pow(10.0, uniform(-55.0, 55.0));
      case 7:
        return coin() ? 0x1p198 : 0x1p-190;
      default:
        return std::pow(10.0, uniform(-3.0, 3.0));
    }
  }

  // A translation: none, or up to 10^8 times the scale (mixed magnitudes).
  Point offset(double s) {
    if (coin(0.4)) return {};
    const double m = std::min(s * std::pow(10.0, uniform(0.0, 8.0)), 0x1p198);
    return {m * uniform(-1.0, 1.0), m * uniform(-1.0, 1.0)};
  }

  Point around(const Point& t, double s) { return {t.x + s * uniform(-1.0, 1.0), t.y + s * uniform(-1.0, 1.0)}; }

  // Perturbs each coordinate by up to k ulps with probability p.
  Point jiggle(Point q, int k, double p = 0.7) {
    if (coin(p)) q.x = ulps(q.x, irange(-k, k));
    if (coin(p)) q.y = ulps(q.y, irange(-k, k));
    return q;
  }

  // A random power of two in [2^lo, 2^hi].
  double pow2(int lo, int hi) { return std::ldexp(1.0, irange(lo, hi)); }

 private:
  std::mt19937_64 rng_;
};

// ---------------------------------------------------------------------------
// Case generators. Each returns inputs inside the supported range.

struct Tri {
  Point p[3];
};
struct Quad {
  Point p[4];
  double w[4] = {0.0, 0.0, 0.0, 0.0};
};

Tri near_collinear(Gen& g) {
  for (;;) {
    Tri t;
    const int mode = g.irange(0, 11);
    if (mode >= 10) {
      // A far-away apex c = lambda * v (v a small integer direction), a and b
      // close to the line through c along v: the coordinate differences are
      // inexact and the determinant mu * det(e, v) is dominated by the
      // product of their roundoff tails (exercises the last exact stage).
      const double s = g.scale();
      const double vx = g.irange(-3, 3), vy = g.coin(0.2) ? 0.0 : g.irange(1, 3);
      const double lambda = s * g.pow2(20, 80);
      const double nu = s * g.uniform(-1.0, 1.0), mu = s * g.uniform(-1.0, 1.0);
      const double tiny = s * g.pow2(-70, -20);
      const Point e = g.coin(0.3) ? Point{} : Point{tiny * g.uniform(-1.0, 1.0), tiny * g.uniform(-1.0, 1.0)};
      const Point a{nu * vx + e.x, nu * vy + e.y};
      const Point b{a.x + mu * vx, a.y + mu * vy};
      t = {{a, b, Point{lambda * vx, lambda * vy}}};
      if (g.coin(0.3)) t.p[1] = g.jiggle(t.p[1], 1);
    } else if (mode <= 5) {
      // c interpolated (or extrapolated) on segment ab, rounded, moved a few ulps.
      const double s = g.scale();
      const Point off = g.offset(s);
      const Point a = g.around(off, s), b = g.around(off, s);
      const double u = g.uniform(-0.5, 1.5);
      Point c{a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)};
      c = g.jiggle(c, 3);
      t = {{a, b, c}};
    } else if (mode <= 7) {
      // Exactly collinear integer points (c = a + k (b - a)), scaled by a power
      // of two and translated on the same lattice; sometimes moved an ulp.
      const double unit = g.pow2(-150, 150);
      const double tx = g.irange(-(1 << 30), 1 << 30), ty = g.irange(-(1 << 30), 1 << 30);
      const int ax = g.irange(-8, 8), ay = g.irange(-8, 8), bx = g.irange(-8, 8), by = g.irange(-8, 8);
      const int k = g.irange(-3, 3);
      const int ci[2] = {ax + k * (bx - ax), ay + k * (by - ay)};
      auto at = [&](double x, double y) { return Point{(tx + x) * unit, (ty + y) * unit}; };
      t = {{at(ax, ay), at(bx, by), at(ci[0], ci[1])}};
      if (g.coin(0.2)) t.p[2] = g.jiggle(t.p[2], 1);
    } else if (mode == 8) {
      // Repeated points.
      const double s = g.scale();
      const Point off = g.offset(s);
      const Point a = g.around(off, s), b = g.around(off, s);
      t = {{a, b, g.coin() ? a : b}};
    } else {
      const double s = g.scale();
      const Point off = g.offset(s);
      t = {{g.around(off, s), g.around(off, s), g.around(off, s)}};
    }
    std::shuffle(std::begin(t.p), std::end(t.p), g.rng());
    if (point_ok(t.p[0]) && point_ok(t.p[1]) && point_ok(t.p[2])) return t;
  }
}

// Lattice points on circles x^2 + y^2 = r^2 centred at the origin.
std::vector<std::array<int, 2>> lattice_circle(int r) {
  std::vector<std::array<int, 2>> pts;
  for (int x = -r; x <= r; ++x) {
    for (int y = -r; y <= r; ++y) {
      if (x * x + y * y == r * r) pts.push_back({x, y});
    }
  }
  return pts;
}

Quad near_cocircular(Gen& g) {
  static const std::vector<std::array<int, 2>> circles[3] = {lattice_circle(5), lattice_circle(25),
                                                             lattice_circle(65)};
  for (;;) {
    Quad q;
    const int mode = g.irange(0, 9);
    if (mode <= 4) {
      // Points on a circle, rounded, some moved a few ulps.
      const double s = g.scale();
      const Point center = g.around(g.offset(s), s);
      const double r = s * g.uniform(0.05, 1.0);
      for (Point& p : q.p) {
        const double th = g.uniform(0.0, 6.283185307179586);
        p = g.jiggle({center.x + r * std::cos(th), center.y + r * std::sin(th)}, 2, 0.5);
      }
      if (g.coin(0.1)) q.p[g.irange(0, 3)] = center;
    } else if (mode <= 6) {
      // Exactly cocircular lattice points, scaled by a power of two and
      // translated on the lattice (exact differences) or off it (inexact).
      const auto& circle = circles[g.irange(0, 2)];
      const double unit = g.pow2(-150, 150);
      const double tx = g.irange(-(1 << 30), 1 << 30), ty = g.irange(-(1 << 30), 1 << 30);
      const bool off_lattice = g.coin(0.25);
      const double fx = off_lattice ? g.uniform(-1.0, 1.0) : 0.0, fy = off_lattice ? g.uniform(-1.0, 1.0) : 0.0;
      for (Point& p : q.p) {
        const auto& c = circle[static_cast<std::size_t>(g.irange(0, static_cast<int>(circle.size()) - 1))];
        p = {(tx + fx + c[0]) * unit, (ty + fy + c[1]) * unit};
      }
      if (g.coin(0.2)) q.p[3] = g.jiggle(q.p[3], 1);
    } else if (mode == 7) {
      // Small grid: rectangles, repeated and collinear points galore.
      const double unit = g.pow2(-150, 150);
      for (Point& p : q.p) p = {g.irange(0, 3) * unit, g.irange(0, 3) * unit};
    } else {
      const double s = g.scale();
      const Point off = g.offset(s);
      for (Point& p : q.p) p = g.around(off, s);
    }
    std::shuffle(std::begin(q.p), std::end(q.p), g.rng());
    if (point_ok(q.p[0]) && point_ok(q.p[1]) && point_ok(q.p[2]) && point_ok(q.p[3])) return q;
  }
}

Quad near_coplanar_lifted(Gen& g) {
  for (;;) {
    Quad q;
    const int mode = g.irange(0, 9);
    if (mode <= 4) {
      // Lifted points x^2 + y^2 - w on (nearly) the plane z = alpha x + beta y + gamma.
      const double s = g.scale();
      const Point off = g.offset(s);
      const double m = std::fabs(off.x) + std::fabs(off.y) + s;
      const double alpha = m * g.uniform(-1.0, 1.0), beta = m * g.uniform(-1.0, 1.0);
      const double gamma = m * m * g.uniform(-1.0, 1.0);
      for (int i = 0; i < 4; ++i) {
        q.p[i] = g.around(off, s);
        const Point& p = q.p[i];
        double w = p.x * p.x + p.y * p.y - (alpha * p.x + beta * p.y + gamma);
        if (g.coin(0.5)) w = ulps(w, g.irange(-2, 2));
        q.w[i] = w;
      }
    } else if (mode <= 6) {
      // Exactly coplanar: integer points and plane, scaled by 2^j (weights 2^2j).
      const int j = g.irange(-90, 90);
      const double unit = std::ldexp(1.0, j), unit2 = std::ldexp(1.0, 2 * j);
      // Plane coefficients: small integers, or up to 2^20 with eight fractional
      // bits (weights with many significant bits below the coordinates' unit).
      const bool wide = g.coin(0.3);
      const double frac = wide ? 0x1p-8 : 1.0;
      const int cmax = wide ? 1 << 28 : 5, gmax = wide ? 1 << 30 : 20;
      const double alpha = g.irange(-cmax, cmax) * frac, beta = g.irange(-cmax, cmax) * frac;
      const double gamma = g.irange(-gmax, gmax) * frac;
      for (int i = 0; i < 4; ++i) {
        const int r = wide ? 1000 : 6;
        const int x = g.irange(-r, r), y = g.irange(-r, r);
        q.p[i] = {x * unit, y * unit};
        q.w[i] = (double(x) * x + double(y) * y - (alpha * x + beta * y + gamma)) * unit2;
      }
      if (g.coin(0.2)) q.w[3] = ulps(q.w[3], g.coin() ? 1 : -1);
    } else if (mode == 7) {
      // Zero weights: near-cocircular points (must agree with incircle).
      const Quad c = near_cocircular(g);
      for (int i = 0; i < 4; ++i) q.p[i] = c.p[i];
    } else {
      const double s = g.scale();
      const Point off = g.offset(s);
      for (int i = 0; i < 4; ++i) {
        q.p[i] = g.around(off, s);
        q.w[i] = s * s * g.uniform(-1.0, 1.0);
      }
    }
    bool ok = true;
    for (int i = 0; i < 4; ++i) ok = ok && point_ok(q.p[i]) && weight_ok(q.w[i]);
    if (ok) return q;
  }
}

double lifted(const Quad& q) {
  return deltamesh::orient3d_lifted(q.p[0], q.p[1], q.p[2], q.p[3], q.w[0], q.w[1], q.w[2], q.w[3]);
}

// Counts of a comparison run; failures keep the first few offending inputs.
struct Tally {
  long mismatches = 0, zeros = 0, nonfinite = 0;
  std::vector<std::string> examples;
  void check(double got, int want, const std::string& what) {
    if (!std::isfinite(got)) ++nonfinite;
    if (want == 0) ++zeros;
    if (sign_of(got) != want) {
      ++mismatches;
      if (examples.size() < 5) examples.push_back(what + " got " + std::to_string(got) + " want sign " + std::to_string(want));
    }
  }
  std::string report() const {
    std::string s;
    for (const auto& e : examples) s += e + "\n";
    return s;
  }
};

std::string describe(const Point* p, int n, const double* w = nullptr) {
  std::string s;
  for (int i = 0; i < n; ++i) {
    s += str(p[i]);
    if (w != nullptr) s += " w=" + std::to_string(w[i]);
    s += " ";
  }
  return s;
}

// ---------------------------------------------------------------------------

TEST(GmpOracle, AgreesWithMpqReference) {
  Gen g(1);
  GmpOracle oracle;
  long bad = 0;
  for (int i = 0; i < 20000; ++i) {
    const Tri t = near_collinear(g);
    bad += oracle.orient2d(t.p[0], t.p[1], t.p[2]) != deltamesh::oracle::orient2d_mpq(t.p[0], t.p[1], t.p[2]);
    const Quad c = near_cocircular(g);
    bad += oracle.incircle(c.p[0], c.p[1], c.p[2], c.p[3]) !=
           deltamesh::oracle::incircle_mpq(c.p[0], c.p[1], c.p[2], c.p[3]);
    const Quad l = near_coplanar_lifted(g);
    bad += oracle.orient3d_lifted(l.p[0], l.p[1], l.p[2], l.p[3], l.w[0], l.w[1], l.w[2], l.w[3]) !=
           deltamesh::oracle::orient3d_lifted_mpq(l.p[0], l.p[1], l.p[2], l.p[3], l.w[0], l.w[1], l.w[2], l.w[3]);
  }
  EXPECT_EQ(bad, 0);
  // Hand-checked values.
  EXPECT_EQ(oracle.orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(oracle.orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(oracle.incircle({1, 0}, {0, 1}, {-1, 0}, {0, 0}), 1);
  EXPECT_EQ(oracle.incircle({1, 0}, {0, 1}, {-1, 0}, {0, -1}), 0);
  EXPECT_EQ(oracle.incircle({1, 0}, {0, 1}, {-1, 0}, {0, -2}), -1);
  EXPECT_EQ(oracle.orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, -1}, 0, 0, 0, 0.5), 1);
  EXPECT_EQ(oracle.orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, -1}, 0.5, 0.5, 0.5, 0.5), 0);
}

TEST(Orient2d, NearCollinearRandomAgainstGmp) {
  Gen g(0x5eed0001);
  GmpOracle oracle;
  Tally tally;
  for (int i = 0; i < kRandomCases; ++i) {
    const Tri t = near_collinear(g);
    const double got = deltamesh::orient2d(t.p[0], t.p[1], t.p[2]);
    const int want = oracle.orient2d(t.p[0], t.p[1], t.p[2]);
    if (sign_of(got) != want || !std::isfinite(got)) tally.check(got, want, describe(t.p, 3));
    else tally.check(got, want, {});
  }
  EXPECT_EQ(tally.mismatches, 0) << tally.report();
  EXPECT_EQ(tally.nonfinite, 0);
  EXPECT_GT(tally.zeros, kRandomCases / 10);  // the exactly degenerate cases are exercised
}

TEST(Incircle, NearCocircularRandomAgainstGmp) {
  Gen g(0x5eed0002);
  GmpOracle oracle;
  Tally tally;
  for (int i = 0; i < kRandomCases; ++i) {
    const Quad q = near_cocircular(g);
    const double got = deltamesh::incircle(q.p[0], q.p[1], q.p[2], q.p[3]);
    const int want = oracle.incircle(q.p[0], q.p[1], q.p[2], q.p[3]);
    if (sign_of(got) != want || !std::isfinite(got)) tally.check(got, want, describe(q.p, 4));
    else tally.check(got, want, {});
  }
  EXPECT_EQ(tally.mismatches, 0) << tally.report();
  EXPECT_EQ(tally.nonfinite, 0);
  EXPECT_GT(tally.zeros, kRandomCases / 10);
}

TEST(Orient3dLifted, NearCoplanarRandomAgainstGmp) {
  Gen g(0x5eed0003);
  GmpOracle oracle;
  Tally tally;
  long zero_weight_disagreements = 0;
  for (int i = 0; i < kRandomCases; ++i) {
    const Quad q = near_coplanar_lifted(g);
    const double got = lifted(q);
    const int want = oracle.orient3d_lifted(q.p[0], q.p[1], q.p[2], q.p[3], q.w[0], q.w[1], q.w[2], q.w[3]);
    if (sign_of(got) != want || !std::isfinite(got)) tally.check(got, want, describe(q.p, 4, q.w));
    else tally.check(got, want, {});
    if (q.w[0] == 0.0 && q.w[1] == 0.0 && q.w[2] == 0.0 && q.w[3] == 0.0) {
      zero_weight_disagreements +=
          sign_of(got) != sign_of(deltamesh::incircle(q.p[0], q.p[1], q.p[2], q.p[3]));
    }
  }
  EXPECT_EQ(tally.mismatches, 0) << tally.report();
  EXPECT_EQ(tally.nonfinite, 0);
  EXPECT_EQ(zero_weight_disagreements, 0);
  EXPECT_GT(tally.zeros, kRandomCases / 10);
}

// Kettner, Mehlhorn, Pion, Schirra, Yap, "Classroom examples of robustness
// problems in geometric computations": orient2d(p, q, r) for p on a 256 x 256
// grid of ulp-steps around a point nearly on the line qr.
TEST(Orient2d, KettnerUlpGridAgainstGmp) {
  struct Setup {
    Point p, q, r;
  };
  const Setup setups[] = {
      {{0.5, 0.5}, {12.0, 12.0}, {24.0, 24.0}},
      {{0.5, 0.5}, {8.8000000000000007, 7.7000000000000002}, {12.1, 12.1}},
      {{0.50000000000002531, 0.5000000000000171}, {17.300000000000001, 17.300000000000001},
       {24.00000000000005, 24.0000000000000517765}},
      {{0.5, 0.5}, {1.0e9 + 0.5, 1.0e9 + 0.5}, {-3.0, -3.0}},
  };
  GmpOracle oracle;
  long mismatches = 0, naive_mismatches = 0, zeros = 0;
  for (const Setup& s : setups) {
    for (int i = 0; i < 256; ++i) {
      for (int j = 0; j < 256; ++j) {
        const Point p{ulps(s.p.x, i), ulps(s.p.y, j)};
        const int want = oracle.orient2d(p, s.q, s.r);
        zeros += want == 0;
        mismatches += sign_of(deltamesh::orient2d(p, s.q, s.r)) != want;
        mismatches += sign_of(deltamesh::orient2d(s.q, s.r, p)) != want;
        mismatches += sign_of(deltamesh::orient2d(s.r, p, s.q)) != want;
        const double naive = (p.x - s.r.x) * (s.q.y - s.r.y) - (p.y - s.r.y) * (s.q.x - s.r.x);
        naive_mismatches += sign_of(naive) != want;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(zeros, 0);
  EXPECT_GT(naive_mismatches, 0);  // the set is adversarial for plain floating point
}

// Exhaustive small grids checked against exact 64-bit integer arithmetic.
TEST(Orient2d, ExhaustiveSmallGrid) {
  const int n = 7;
  std::vector<Point> pts;
  for (int x = 0; x < n; ++x)
    for (int y = 0; y < n; ++y) pts.push_back({static_cast<double>(x), static_cast<double>(y)});
  long mismatches = 0;
  for (const Point& a : pts)
    for (const Point& b : pts)
      for (const Point& c : pts) {
        const auto want = static_cast<long>((a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x));
        // Same grid scaled by 2^-60 and translated by 2^40 units: exact, non-trivial exponents.
        const double u = 0x1p-60, t = 0x1p-20;
        const Point a2{t + a.x * u, t + a.y * u}, b2{t + b.x * u, t + b.y * u}, c2{t + c.x * u, t + c.y * u};
        mismatches += sign_of(deltamesh::orient2d(a, b, c)) != (want > 0) - (want < 0);
        mismatches += sign_of(deltamesh::orient2d(a2, b2, c2)) != (want > 0) - (want < 0);
      }
  EXPECT_EQ(mismatches, 0);
}

TEST(Incircle, ExhaustiveSmallGrid) {
  const int n = 5;
  std::vector<std::array<long, 2>> pts;
  for (long x = 0; x < n; ++x)
    for (long y = 0; y < n; ++y) pts.push_back({x, y});
  long mismatches = 0, zeros = 0;
  const double t = 0x1p30;  // translation: coordinates need 33 bits, differences exact
  for (const auto& a : pts)
    for (const auto& b : pts)
      for (const auto& c : pts)
        for (const auto& d : pts) {
          const long adx = a[0] - d[0], ady = a[1] - d[1], bdx = b[0] - d[0], bdy = b[1] - d[1];
          const long cdx = c[0] - d[0], cdy = c[1] - d[1];
          const long det = (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) +
                           (bdx * bdx + bdy * bdy) * (cdx * ady - adx * cdy) +
                           (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
          const int want = (det > 0) - (det < 0);
          zeros += want == 0;
          auto P = [&](const std::array<long, 2>& q, double off) {
            return Point{off + static_cast<double>(q[0]), off + static_cast<double>(q[1])};
          };
          mismatches += sign_of(deltamesh::incircle(P(a, 0), P(b, 0), P(c, 0), P(d, 0))) != want;
          mismatches += sign_of(deltamesh::incircle(P(a, t), P(b, t), P(c, t), P(d, t))) != want;
        }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(zeros, 0);
}

// A 1000 x 1000 integer grid is all cocircular: rectangles and isosceles
// trapezoids of grid points have incircle exactly 0 in every order.
TEST(Incircle, CocircularIntegerGridIsExactlyZero) {
  Gen g(7);
  long nonzero = 0;
  for (int it = 0; it < 200000; ++it) {
    const double scale = it % 2 == 0 ? 1.0 : g.pow2(-100, 100);
    const int x0 = g.irange(0, 998), y0 = g.irange(0, 998);
    const int w = g.irange(1, 999 - x0), h = g.irange(1, 999 - y0);
    std::array<Point, 4> q;
    if (it % 3 == 0) {
      // Isosceles trapezoid: symmetric about x = x0 + w / 2.
      const int inset = g.irange(0, (w - 1) / 2);
      q = {Point{double(x0), double(y0)}, Point{double(x0 + w), double(y0)},
           Point{double(x0 + w - inset), double(y0 + h)}, Point{double(x0 + inset), double(y0 + h)}};
    } else {
      q = {Point{double(x0), double(y0)}, Point{double(x0 + w), double(y0)}, Point{double(x0 + w), double(y0 + h)},
           Point{double(x0), double(y0 + h)}};
    }
    for (Point& p : q) p = {p.x * scale, p.y * scale};
    std::shuffle(q.begin(), q.end(), g.rng());
    nonzero += deltamesh::incircle(q[0], q[1], q[2], q[3]) != 0.0;
    nonzero += lifted({{q[0], q[1], q[2], q[3]}}) != 0.0;
  }
  EXPECT_EQ(nonzero, 0);

  // Rectangles and trapezoids whose integer differences span 8..16 bits (the
  // plain floating-point shortcut stops being exact around 12), sometimes
  // with one corner moved by one unit, against GMP.
  GmpOracle oracle;
  long mismatches = 0;
  for (int it = 0; it < 200000; ++it) {
    const int bits = g.irange(8, 16);
    const int top = (1 << bits) - 1;
    const int x0 = g.irange(0, top - 2), y0 = g.irange(0, top - 2);
    const int w = g.irange(2, top - x0), h = g.irange(1, top - y0);
    const int inset = it % 2 == 0 ? 0 : g.irange(0, (w - 1) / 2);
    std::array<Point, 4> q = {Point{double(x0), double(y0)}, Point{double(x0 + w), double(y0)},
                              Point{double(x0 + w - inset), double(y0 + h)}, Point{double(x0 + inset), double(y0 + h)}};
    if (g.coin(0.3)) {
      Point& p = q[static_cast<std::size_t>(g.irange(0, 3))];
      (g.coin() ? p.x : p.y) += g.coin() ? 1.0 : -1.0;
    }
    std::shuffle(q.begin(), q.end(), g.rng());
    const double got = deltamesh::incircle(q[0], q[1], q[2], q[3]);
    mismatches += sign_of(got) != oracle.incircle(q[0], q[1], q[2], q[3]);
    const double wunit = g.pow2(-4, 12);
    const double weights[4] = {g.irange(-top, top) * wunit, 0.0, g.irange(-top, top) * wunit, 0.0};
    const double lw = deltamesh::orient3d_lifted(q[0], q[1], q[2], q[3], weights[0], weights[1], weights[2], weights[3]);
    mismatches += sign_of(lw) != oracle.orient3d_lifted(q[0], q[1], q[2], q[3], weights[0], weights[1], weights[2],
                                                        weights[3]);
  }
  EXPECT_EQ(mismatches, 0);

  // Lattice points of the circle of radius 65 (many of them), translated.
  const auto circle = lattice_circle(65);
  for (std::size_t i = 0; i + 3 < circle.size(); ++i) {
    auto P = [&](std::size_t k) { return Point{1.0e6 + circle[k][0], -1.0e6 + circle[k][1]}; };
    EXPECT_EQ(deltamesh::incircle(P(i), P(i + 1), P(i + 2), P(i + 3)), 0.0);
  }
}

// Swapping two arguments flips the sign; cyclic shifts keep it.
TEST(Predicates, SignSymmetry) {
  Gen g(11);
  long bad = 0;
  for (int i = 0; i < 100000; ++i) {
    const Tri t = near_collinear(g);
    const Point &a = t.p[0], &b = t.p[1], &c = t.p[2];
    const int s = sign_of(deltamesh::orient2d(a, b, c));
    bad += sign_of(deltamesh::orient2d(b, c, a)) != s;
    bad += sign_of(deltamesh::orient2d(c, a, b)) != s;
    bad += sign_of(deltamesh::orient2d(b, a, c)) != -s;
    bad += sign_of(deltamesh::orient2d(a, c, b)) != -s;

    const Quad q = near_cocircular(g);
    const Point &p0 = q.p[0], &p1 = q.p[1], &p2 = q.p[2], &p3 = q.p[3];
    const int r = sign_of(deltamesh::incircle(p0, p1, p2, p3));
    bad += sign_of(deltamesh::incircle(p1, p2, p0, p3)) != r;
    bad += sign_of(deltamesh::incircle(p1, p0, p2, p3)) != -r;
    bad += sign_of(deltamesh::incircle(p3, p1, p2, p0)) != -r;
    bad += sign_of(deltamesh::incircle(p0, p1, p3, p2)) != -r;

    const Quad l = near_coplanar_lifted(g);
    const auto L = [&](int i0, int i1, int i2, int i3) {
      return sign_of(deltamesh::orient3d_lifted(l.p[i0], l.p[i1], l.p[i2], l.p[i3], l.w[i0], l.w[i1], l.w[i2],
                                                l.w[i3]));
    };
    const int m = L(0, 1, 2, 3);
    bad += L(1, 2, 0, 3) != m;
    bad += L(1, 0, 2, 3) != -m;
    bad += L(3, 1, 2, 0) != -m;
    bad += L(0, 1, 3, 2) != -m;
  }
  EXPECT_EQ(bad, 0);
}

TEST(Predicates, BasicConventions) {
  EXPECT_GT(deltamesh::orient2d({0, 0}, {1, 0}, {0, 1}), 0.0);
  EXPECT_LT(deltamesh::orient2d({0, 0}, {0, 1}, {1, 0}), 0.0);
  EXPECT_EQ(deltamesh::orient2d({0, 0}, {1, 1}, {3, 3}), 0.0);
  EXPECT_GT(deltamesh::incircle({1, 0}, {0, 1}, {-1, 0}, {0, 0}), 0.0);
  EXPECT_EQ(deltamesh::incircle({1, 0}, {0, 1}, {-1, 0}, {0, -1}), 0.0);
  EXPECT_LT(deltamesh::incircle({1, 0}, {0, 1}, {-1, 0}, {0, -2}), 0.0);
  // Weighted: a heavier d is "more inside"; equal weights change nothing.
  EXPECT_GT(deltamesh::orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, -1}, 0, 0, 0, 0.25), 0.0);
  EXPECT_LT(deltamesh::orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, -1}, 0, 0, 0, -0.25), 0.0);
  EXPECT_EQ(deltamesh::orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, -1}, 3, 3, 3, 3), 0.0);
  EXPECT_LT(deltamesh::orient3d_lifted({1, 0}, {0, 1}, {-1, 0}, {0, 0}, 0, 0, 0, -2), 0.0);
}

// Right at the limits of the supported range, where overflow or underflow
// would show up first.
TEST(Predicates, RangeLimitsAgainstGmp) {
  Gen g(13);
  GmpOracle oracle;
  const double big = deltamesh::kMaxCoordinate, small = deltamesh::kMinCoordinate;
  long mismatches = 0, nonfinite = 0;
  auto clamp = [&](Point p) {
    p.x = std::max(-big, std::min(big, p.x));
    p.y = std::max(-big, std::min(big, p.y));
    return p;
  };
  for (int i = 0; i < 20000; ++i) {
    // Huge: corners and a near-collinear / near-cocircular point at full scale.
    const Point a{-big, -big}, b{big, g.coin() ? big : -big};
    const double u = g.uniform(0.0, 1.0);
    const Point c = clamp(g.jiggle({a.x + u * (b.x - a.x), a.y + u * (b.y - a.y)}, 2));
    const double o = oracle.orient2d(a, b, c);
    const double r = deltamesh::orient2d(a, b, c);
    mismatches += sign_of(r) != o;
    nonfinite += !std::isfinite(r);

    Point q[4];
    for (Point& p : q) {
      const double th = g.uniform(0.0, 6.283185307179586);
      p = clamp(g.jiggle({big * std::cos(th), big * std::sin(th)}, 2, 0.5));
    }
    const double ic = deltamesh::incircle(q[0], q[1], q[2], q[3]);
    mismatches += sign_of(ic) != oracle.incircle(q[0], q[1], q[2], q[3]);
    nonfinite += !std::isfinite(ic);
    const double wmax = deltamesh::kMaxWeight;
    const double w[4] = {wmax * g.uniform(-1, 1), wmax * g.uniform(-1, 1), wmax * g.uniform(-1, 1),
                         g.coin() ? wmax : -wmax};
    const double lw = deltamesh::orient3d_lifted(q[0], q[1], q[2], q[3], w[0], w[1], w[2], w[3]);
    mismatches += sign_of(lw) != oracle.orient3d_lifted(q[0], q[1], q[2], q[3], w[0], w[1], w[2], w[3]);
    nonfinite += !std::isfinite(lw);

    // Tiny: coordinates of magnitude 2^-200 .. 2^-198 with full 53-bit
    // significands, so differences reach down to 2^-252.
    auto tiny = [&] {
      const double m = small * g.uniform(1.0, 4.0);
      return g.coin(0.1) ? 0.0 : (g.coin() ? m : -m);
    };
    Point t[4];
    for (Point& p : t) p = {tiny(), tiny()};
    const Point tc = g.jiggle({t[0].x + u * (t[1].x - t[0].x), t[0].y + u * (t[1].y - t[0].y)}, 2);
    if (point_ok(tc)) {
      const double v = deltamesh::orient2d(t[0], t[1], tc);
      mismatches += sign_of(v) != oracle.orient2d(t[0], t[1], tc);
    }
    const double tv = deltamesh::incircle(t[0], t[1], t[2], t[3]);
    mismatches += sign_of(tv) != oracle.incircle(t[0], t[1], t[2], t[3]);
    const double wmin = deltamesh::kMinWeight;
    const double tw[4] = {wmin * g.uniform(1, 4), 0.0, -wmin * g.uniform(1, 4), wmin};
    const double tl = deltamesh::orient3d_lifted(t[0], t[1], t[2], t[3], tw[0], tw[1], tw[2], tw[3]);
    mismatches += sign_of(tl) != oracle.orient3d_lifted(t[0], t[1], t[2], t[3], tw[0], tw[1], tw[2], tw[3]);
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(nonfinite, 0);
}

// ---------------------------------------------------------------------------
// check_coordinates / check_weights

void expect_rejected(const std::vector<Point>& pts, std::size_t index, const std::string& fragment) {
  try {
    deltamesh::check_coordinates(pts);
    ADD_FAILURE() << "accepted a bad point at index " << index;
  } catch (const deltamesh::InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.index(), index) << what;
    EXPECT_NE(what.find("point " + std::to_string(index)), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(CheckCoordinates, RejectsBadValuesNamingTheIndex) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Point> pts(40, Point{1.0, 2.0});
  auto with = [&](std::size_t i, Point p) {
    auto v = pts;
    v[i] = p;
    return v;
  };
  expect_rejected(with(17, {1.0, nan}), 17, "NaN");
  expect_rejected(with(3, {nan, 0.0}), 3, "NaN");
  expect_rejected(with(0, {inf, 0.0}), 0, "infinite");
  expect_rejected(with(39, {0.0, -inf}), 39, "infinite");
  expect_rejected(with(21, {1e200, 0.0}), 21, "overflow");
  expect_rejected(with(22, {0.0, -1e61}), 22, "exceeds");
  expect_rejected(with(5, {std::nextafter(deltamesh::kMaxCoordinate, inf), 0.0}), 5, "overflow");
  expect_rejected(with(8, {1e-300, 1.0}), 8, "underflow");
  expect_rejected(with(9, {1.0, -5e-324}), 9, "underflow");
  expect_rejected(with(10, {1.0, std::nextafter(deltamesh::kMinCoordinate, 0.0)}), 10, "underflow");
  // The first offender is reported.
  auto two = pts;
  two[30] = {nan, nan};
  two[12] = {1e300, 1.0};
  expect_rejected(two, 12, "exceeds");
  // The message names the coordinate.
  try {
    deltamesh::check_coordinates(with(17, {0.0, nan}));
  } catch (const deltamesh::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("coordinate y of point 17"), std::string::npos) << e.what();
  }
}

TEST(CheckCoordinates, AcceptsSupportedRange) {
  const std::vector<Point> ok = {
      {0.0, 0.0},
      {-0.0, 0.0},
      {1e-9, -1e-9},
      {1e9, -1e9},
      {1e-30, 1e30},
      {1e60, -1e-60},
      {deltamesh::kMaxCoordinate, -deltamesh::kMaxCoordinate},
      {deltamesh::kMinCoordinate, -deltamesh::kMinCoordinate},
      {0.1, 12345.678},
  };
  EXPECT_NO_THROW(deltamesh::check_coordinates(ok));
  EXPECT_NO_THROW(deltamesh::check_coordinates(std::vector<Point>{}));
  EXPECT_EQ(deltamesh::kMaxCoordinate, 0x1p200);
  EXPECT_EQ(deltamesh::kMinCoordinate, 0x1p-200);
}

TEST(CheckWeights, RangeAndMessages) {
  const std::vector<double> ok = {0.0, 1.0, -1e100, 1e-100, deltamesh::kMaxWeight, deltamesh::kMinWeight};
  EXPECT_NO_THROW(deltamesh::check_weights(ok));
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e150,
                        1e-150};
  for (double b : bad) {
    std::vector<double> w(10, 1.0);
    w[6] = b;
    try {
      deltamesh::check_weights(w);
      ADD_FAILURE() << "accepted weight " << b;
    } catch (const deltamesh::InputError& e) {
      EXPECT_EQ(e.index(), 6u);
      EXPECT_NE(std::string(e.what()).find("point 6"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
