#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/embed/tutte.h"
#include "igm/mesh/generate.h"

using namespace igm;

namespace {

Rational q(long a, long b = 1) { return make_rational(Integer(a), Integer(b)); }

struct DiskMesh {
  int nv = 0;
  std::vector<std::array<int, 3>> tris;
  std::vector<int> boundary;
  std::vector<Point2q> buv;
};

// Independent certificate: every triangle strictly positive by the exact rational predicate,
// boundary vertices exactly where they were asked to be.
void check_embedding(const DiskMesh& d, const TutteResult& r, bool forced = false) {
  REQUIRE(r.uv.size() == static_cast<std::size_t>(d.nv));
  std::int64_t bad = 0;
  for (const auto& t : d.tris)
    if (orient2d(r.uv[t[0]], r.uv[t[1]], r.uv[t[2]]) != Sign::Positive) ++bad;
  CHECK(bad == 0);
  bool boundary_fixed = true;
  for (std::size_t i = 0; i < d.boundary.size(); ++i)
    if (r.uv[d.boundary[i]].x != d.buv[i].x || r.uv[d.boundary[i]].y != d.buv[i].y) boundary_fixed = false;
  CHECK(boundary_fixed);
  // Interior vertices: Tutte's equations hold only approximately unless the fallback ran, but
  // every interior vertex must lie strictly inside the convex boundary polygon, which follows
  // from positivity; checked implicitly. The statistics must agree with the certificate.
  CHECK(r.stats.triangles == static_cast<int>(d.tris.size()));
  CHECK(r.stats.interior_vertices + r.stats.boundary_vertices == d.nv);
  if (!r.stats.flips_per_iteration.empty()) CHECK(r.stats.flips_per_iteration.back() == 0);
  if (r.stats.flips_double == 0 && !forced) CHECK(r.stats.iterations == 0);
}

TutteResult embed(const DiskMesh& d, const TutteOptions& o = {}) {
  return tutte_embed(d.nv, d.tris, d.boundary, d.buv, o);
}

// (n+1)^2 grid, boundary on a polygon given by four corners, i/n steps; random diagonals.
DiskMesh grid_disk(int n, std::uint64_t seed, const std::array<Point2q, 4>& corners) {
  DiskMesh d;
  d.nv = (n + 1) * (n + 1);
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  std::mt19937_64 rng(seed);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
      if (rng() & 1) {
        d.tris.push_back({a, b, c});
        d.tris.push_back({a, c, e});
      } else {
        d.tris.push_back({a, b, e});
        d.tris.push_back({b, c, e});
      }
    }
  std::vector<Point2q> cs(corners.begin(), corners.end());
  d.buv = place_boundary(cs, {n, n, n, n});
  for (int i = 0; i < n; ++i) d.boundary.push_back(id(i, 0));
  for (int j = 0; j < n; ++j) d.boundary.push_back(id(n, j));
  for (int i = n; i > 0; --i) d.boundary.push_back(id(i, n));
  for (int j = n; j > 0; --j) d.boundary.push_back(id(0, j));
  return d;
}
std::array<Point2q, 4> unit_square() {
  return {Point2q{q(0), q(0)}, Point2q{q(1), q(0)}, Point2q{q(1), q(1)}, Point2q{q(0), q(1)}};
}

// Concentric rings inside a boundary polygon: ring 0 is the boundary (B vertices), `rings`
// inner rings of B vertices, one centre. With few vertices per ring and many rings this is a
// long thin tube whose Tutte image shrinks geometrically towards its end.
DiskMesh rings_disk(const std::vector<Point2q>& boundary_uv, int rings) {
  DiskMesh d;
  const int B = static_cast<int>(boundary_uv.size());
  d.nv = B * (rings + 1) + 1;
  auto id = [&](int k, int i) { return k * B + ((i % B) + B) % B; };
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < B; ++i) {
      d.tris.push_back({id(k, i), id(k, i + 1), id(k + 1, i + 1)});
      d.tris.push_back({id(k, i), id(k + 1, i + 1), id(k + 1, i)});
    }
  const int centre = d.nv - 1;
  for (int i = 0; i < B; ++i) d.tris.push_back({id(rings, i), id(rings, i + 1), centre});
  for (int i = 0; i < B; ++i) d.boundary.push_back(id(0, i));
  d.buv = boundary_uv;
  return d;
}

// A closed generated mesh with one face removed; boundary on the triangle (0,0),(1,0),(0,1).
DiskMesh punctured_sphere(std::int64_t faces, std::uint64_t seed, int genus = 0) {
  const PolygonSoup s = generate_closed_mesh({genus, faces, seed, true, 0.25});
  DiskMesh d;
  d.nv = static_cast<int>(s.positions.size());
  for (std::size_t f = 1; f < s.num_faces(); ++f) {
    const auto* c = &s.corners[s.face_begin[f]];
    d.tris.push_back({int(c[0]), int(c[1]), int(c[2])});
  }
  const auto* c = &s.corners[s.face_begin[0]];
  d.boundary = {int(c[0]), int(c[2]), int(c[1])};  // the hole's boundary, reversed face 0
  d.buv = {{q(0), q(0)}, {q(1), q(0)}, {q(0), q(1)}};
  return d;
}

// Deeply nested triangles at corner A of the boundary triangle A B C: each new vertex is
// inserted into the triangle of the previous step that contains A, alternating between its two
// sub-triangles at A, so the vertices converge geometrically to A.
DiskMesh nested_disk(int depth, const std::array<Point2q, 3>& abc) {
  DiskMesh d;
  d.nv = 3;
  d.boundary = {0, 1, 2};
  d.buv = {abc[0], abc[1], abc[2]};
  std::array<int, 3> cur = {0, 1, 2};  // (A, p, q), counter-clockwise
  std::vector<std::array<int, 3>> done;
  for (int k = 0; k < depth; ++k) {
    const int v = d.nv++;
    const int A = cur[0], p = cur[1], r = cur[2];
    done.push_back({p, r, v});
    if (k % 2 == 0) {
      done.push_back({r, A, v});
      cur = {A, p, v};
    } else {
      done.push_back({A, p, v});
      cur = {A, v, r};
    }
  }
  done.push_back(cur);
  d.tris = done;
  return d;
}

// Dense fan: boundary triangle A B C; interior path P1..Pn from C towards AB, each Pi adjacent
// to both A and B (A and B get valence n + 2). The Tutte positions approach the midpoint of AB
// like (2 - sqrt 3)^i.
DiskMesh fan_disk(int n, const std::array<Point2q, 3>& abc) {
  DiskMesh d;
  d.nv = 3 + n;
  const int A = 0, B = 1, C = 2;
  auto P = [&](int i) { return i == 0 ? C : 2 + i; };
  for (int i = 0; i < n; ++i) {
    d.tris.push_back({A, P(i + 1), P(i)});
    d.tris.push_back({B, P(i), P(i + 1)});
  }
  d.tris.push_back({A, B, P(n)});
  d.boundary = {A, B, C};
  d.buv = {abc[0], abc[1], abc[2]};
  return d;
}

// Random edge flips and vertex insertions on a disk (combinatorially valid by construction:
// a flip is done only if the new edge is new and does not join two boundary vertices).
void randomize(DiskMesh& d, int ops, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::set<int> bset(d.boundary.begin(), d.boundary.end());
  for (int op = 0; op < ops; ++op) {
    if (rng() % 3 == 0) {
      const std::size_t f = rng() % d.tris.size();
      const auto t = d.tris[f];
      const int v = d.nv++;
      d.tris[f] = {t[0], t[1], v};
      d.tris.push_back({t[1], t[2], v});
      d.tris.push_back({t[2], t[0], v});
      continue;
    }
    std::map<std::pair<int, int>, std::pair<int, int>> he;  // (a,b) -> (face, corner of a)
    for (int f = 0; f < static_cast<int>(d.tris.size()); ++f)
      for (int i = 0; i < 3; ++i) he[{d.tris[f][i], d.tris[f][(i + 1) % 3]}] = {f, i};
    const int f = static_cast<int>(rng() % d.tris.size());
    const int i = static_cast<int>(rng() % 3);
    const int a = d.tris[f][i], b = d.tris[f][(i + 1) % 3], c = d.tris[f][(i + 2) % 3];
    auto it = he.find({b, a});
    if (it == he.end()) continue;
    const auto [g, j] = it->second;
    const int e = d.tris[g][(j + 2) % 3];
    if (c == e || he.count({c, e}) || he.count({e, c})) continue;
    if (bset.count(c) && bset.count(e)) continue;
    d.tris[f] = {c, a, e};
    d.tris[g] = {e, b, c};
  }
}

template <class F>
void expect_invalid(F&& f, const std::string& fragment) {
  try {
    f();
    FAIL("no error thrown, expected: " << fragment);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::InvalidArgument);
    const std::string what = e.what();
    CHECK_MESSAGE(what.find(fragment) != std::string::npos, what);
  }
}

}  // namespace

TEST_CASE("grid disk on the unit square: certified, 1/3 boundary steps") {
  for (int n : {3, 10, 30}) {
    CAPTURE(n);
    const DiskMesh d = grid_disk(n, 7 + n, unit_square());
    const TutteResult r = embed(d);
    check_embedding(d, r);
    CHECK(r.stats.interior_vertices == (n - 1) * (n - 1));
  }
  // Boundary 1/3 steps: exact thirds.
  const DiskMesh d = grid_disk(3, 1, unit_square());
  CHECK(d.buv[1].x == q(1, 3));
  const TutteResult r = embed(d);
  CHECK(r.uv[d.boundary[1]].x == q(1, 3));
  // On a 3x3 grid every interior vertex of the exact Tutte solution is a fixed rational; the
  // result is certified, not necessarily exact, but near the exact solution.
  check_embedding(d, r);
}

TEST_CASE("closed generated mesh minus one face: certified on a triangle") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const DiskMesh d = punctured_sphere(3000, seed);
    const TutteResult r = embed(d);
    check_embedding(d, r);
  }
}

TEST_CASE("random triangulated disks, boundary on 4g-gons with general rational positions") {
  for (int g : {1, 2, 3}) {
    const auto corners = canonical_polygon(g);
    std::vector<int> counts(4 * g);
    for (int s = 0; s < 4 * g; ++s) counts[s] = 1 + (s * 7 + g) % 4;
    const auto buv = place_boundary(corners, counts);
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      CAPTURE(g);
      CAPTURE(seed);
      DiskMesh d = rings_disk(buv, 3);
      randomize(d, 400, seed * 31 + g);
      const TutteResult r = embed(d);
      check_embedding(d, r);
    }
  }
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    DiskMesh d = grid_disk(6, seed, unit_square());
    randomize(d, 600, seed);
    check_embedding(d, embed(d));
  }
}

TEST_CASE("adversarial: deeply nested triangles flip in double, refinement certifies them") {
  const std::array<Point2q, 3> abc = {Point2q{q(1), q(1)}, Point2q{q(2), q(1)}, Point2q{q(1), q(2)}};
  const DiskMesh d = nested_disk(120, abc);
  const TutteResult r = embed(d);
  MESSAGE("nested: flips_double " << r.stats.flips_double << ", iterations " << r.stats.iterations
                                  << ", max bits " << r.stats.max_bits);
  CHECK(r.stats.flips_double > 0);
  CHECK(r.stats.iterations > 0);
  CHECK_FALSE(r.stats.exact_fallback);
  check_embedding(d, r);
}

TEST_CASE("adversarial: long thin tube shrinks below double precision, refinement certifies it") {
  const auto sq = canonical_polygon(1);
  const DiskMesh d = rings_disk(sq, 60);
  const TutteResult r = embed(d);
  MESSAGE("tube: flips_double " << r.stats.flips_double << ", iterations " << r.stats.iterations
                                << ", max bits " << r.stats.max_bits);
  CHECK(r.stats.flips_double > 0);
  CHECK_FALSE(r.stats.exact_fallback);
  check_embedding(d, r);
}

TEST_CASE("adversarial: long thin strip in a sliver rectangle is degenerate in double") {
  // A 40x2 grid strip on the rectangle [1,2] x [1, 1 + 2^-60]: the doubles cannot separate the
  // rows, every triangle is flat in double.
  const Rational h = make_rational(Integer(1), Integer(1) << 60);
  const std::array<Point2q, 4> rect = {Point2q{q(1), q(1)}, Point2q{q(2), q(1)},
                                       Point2q{q(2), Rational(1 + h)}, Point2q{q(1), Rational(1 + h)}};
  const DiskMesh d = grid_disk(8, 5, rect);
  const TutteResult r = embed(d);
  MESSAGE("strip: flips_double " << r.stats.flips_double << ", iterations " << r.stats.iterations);
  CHECK(r.stats.flips_double > 0);
  check_embedding(d, r);
}

TEST_CASE("adversarial: dense fan collapses onto an edge in double, refinement certifies it") {
  const std::array<Point2q, 3> abc = {Point2q{q(0), q(1)}, Point2q{q(1), q(1)}, Point2q{q(1, 2), q(2)}};
  const DiskMesh d = fan_disk(200, abc);
  const TutteResult r = embed(d);
  MESSAGE("fan: flips_double " << r.stats.flips_double << ", iterations " << r.stats.iterations
                               << ", max bits " << r.stats.max_bits);
  CHECK(r.stats.flips_double > 0);
  CHECK(r.stats.iterations >= 2);
  CHECK(r.stats.flips_per_iteration.size() == static_cast<std::size_t>(r.stats.iterations));
  check_embedding(d, r);
}

TEST_CASE("iteration bound hit: exact rational fallback solves Tutte exactly") {
  const std::array<Point2q, 3> abc = {Point2q{q(0), q(1)}, Point2q{q(1), q(1)}, Point2q{q(1, 3), q(2)}};
  const DiskMesh d = fan_disk(60, abc);
  TutteOptions o;
  o.max_iterations = 0;
  const TutteResult r = embed(d, o);
  CHECK(r.stats.flips_double > 0);
  CHECK(r.stats.exact_fallback);
  CHECK(r.stats.iterations == 0);
  check_embedding(d, r);
  // The exact solution satisfies Tutte's equations exactly: each path vertex is the mean of
  // its four neighbours.
  auto P = [&](int i) { return i == 0 ? 2 : 2 + i; };
  bool exact = true;
  for (int i = 1; i < 60; ++i) {
    const Rational sx = r.uv[0].x + r.uv[1].x + r.uv[P(i - 1)].x + r.uv[P(i + 1)].x;
    const Rational sy = r.uv[0].y + r.uv[1].y + r.uv[P(i - 1)].y + r.uv[P(i + 1)].y;
    if (4 * r.uv[P(i)].x != sx || 4 * r.uv[P(i)].y != sy) exact = false;
  }
  CHECK(exact);
  // Beyond the fallback size: a typed internal error with the statistics.
  o.exact_fallback_max_interior = 10;
  try {
    embed(d, o);
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Internal);
    CHECK(std::string(e.what()).find("interior vertices 60") != std::string::npos);
  }
}

TEST_CASE("all vertices on the boundary: the placement itself, checked") {
  // A convex pentagon fan-triangulated from vertex 0.
  DiskMesh d;
  d.nv = 5;
  d.tris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  d.boundary = {0, 1, 2, 3, 4};
  d.buv = {{q(0), q(0)}, {q(2), q(0)}, {q(3), q(1)}, {q(1), q(3)}, {q(-1), q(1)}};
  const TutteResult r = embed(d);
  check_embedding(d, r);
  CHECK(r.stats.interior_vertices == 0);
}

TEST_CASE("pre-condition violations are typed errors naming the element") {
  const DiskMesh g = grid_disk(3, 1, unit_square());
  SUBCASE("reversed boundary orientation") {
    DiskMesh d = g;
    std::reverse(d.boundary.begin(), d.boundary.end());
    expect_invalid([&] { embed(d); }, "opposite orientation");
  }
  SUBCASE("boundary cycle not the mesh boundary") {
    DiskMesh d = g;
    std::swap(d.boundary[1], d.boundary[2]);
    expect_invalid([&] { embed(d); }, "boundary");
  }
  SUBCASE("non-convex boundary positions") {
    DiskMesh d = g;
    d.buv[1].y = q(1, 2);  // pushes a bottom vertex inwards: a reflex turn
    expect_invalid([&] { embed(d); }, "clockwise");
  }
  SUBCASE("index out of range / repeated vertex / unused vertex") {
    DiskMesh d = g;
    d.tris[0][1] = 99;
    expect_invalid([&] { embed(d); }, "outside");
    d = g;
    d.tris[0][1] = d.tris[0][0];
    expect_invalid([&] { embed(d); }, "repeats a vertex");
    d = g;
    d.nv += 1;
    expect_invalid([&] { embed(d); }, "used by no triangle");
  }
  SUBCASE("two boundary loops (annulus)") {
    DiskMesh d = rings_disk(canonical_polygon(1), 2);
    d.tris.resize(d.tris.size() - 4);  // drop the centre and its four triangles: a hole
    d.nv -= 1;
    expect_invalid([&] { embed(d); }, "several boundary loops");
  }
  SUBCASE("handle inside: genus 1 mesh minus a face") {
    const DiskMesh d = punctured_sphere(400, 3, 1);
    expect_invalid([&] { embed(d); }, "Euler characteristic");
  }
  SUBCASE("interior edge between two vertices of one side") {
    DiskMesh d;
    d.nv = 7;
    d.tris = {{0, 1, 6}, {1, 2, 6}, {2, 0, 6}, {0, 2, 5}, {2, 3, 4}, {2, 4, 5}};
    d.boundary = {0, 1, 2, 3, 4, 5};
    d.buv = {{q(0), q(0)}, {q(1, 3), q(0)}, {q(2, 3), q(0)}, {q(1), q(0)}, {q(1), q(1)}, {q(0), q(1)}};
    try {
      embed(d);
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::InvalidArgument);
      CHECK(std::string(e.what()).find("same polygon side") != std::string::npos);
      CHECK(e.elements() == std::vector<std::int64_t>{0, 2});
    }
  }
  SUBCASE("triangle with three vertices on one side") {
    DiskMesh d;
    d.nv = 5;
    d.tris = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
    d.boundary = {0, 1, 2, 3, 4};
    d.buv = {{q(0), q(0)}, {q(1, 2), q(0)}, {q(1), q(0)}, {q(1), q(1)}, {q(0), q(1)}};
    try {
      embed(d);
      FAIL("no error");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::InvalidArgument);
      CHECK(e.elements() == std::vector<std::int64_t>{0});
    }
  }
  SUBCASE("pinched vertex (two fans)") {
    // Two triangles of a disk sharing only a vertex... plus a bridge so the boundary is one loop:
    // a bow-tie has one boundary loop through the pinch twice.
    DiskMesh d;
    d.nv = 5;
    d.tris = {{0, 1, 2}, {0, 3, 4}};
    d.boundary = {0, 1, 2, 3, 4};
    d.buv = {{q(0), q(0)}, {q(1), q(0)}, {q(1), q(1)}, {q(0), q(1)}, {q(-1), q(1, 2)}};
    expect_invalid([&] { embed(d); }, "pinched");
  }
  SUBCASE("inconsistent orientation") {
    DiskMesh d = g;
    std::swap(d.tris[4][1], d.tris[4][2]);
    expect_invalid([&] { embed(d); }, "same direction");
  }
}

namespace {
// The exact Tutte solution by dense rational Gauss-Jordan elimination (independent of the
// library's solvers; small meshes only).
std::vector<Point2q> exact_tutte(const DiskMesh& d) {
  std::vector<int> bpos(d.nv, -1), idx(d.nv, -1);
  for (std::size_t i = 0; i < d.boundary.size(); ++i) bpos[d.boundary[i]] = static_cast<int>(i);
  int m = 0;
  for (int v = 0; v < d.nv; ++v)
    if (bpos[v] < 0) idx[v] = m++;
  std::vector<std::set<int>> nbr(d.nv);
  for (const auto& t : d.tris)
    for (int i = 0; i < 3; ++i) {
      nbr[t[i]].insert(t[(i + 1) % 3]);
      nbr[t[(i + 1) % 3]].insert(t[i]);
    }
  std::vector<std::vector<Rational>> M(m, std::vector<Rational>(m + 2, Rational(0)));
  for (int v = 0; v < d.nv; ++v) {
    if (idx[v] < 0) continue;
    const int i = idx[v];
    M[i][i] = static_cast<long>(nbr[v].size());
    for (int w : nbr[v]) {
      if (idx[w] >= 0)
        M[i][idx[w]] -= 1;
      else {
        M[i][m] += d.buv[bpos[w]].x;
        M[i][m + 1] += d.buv[bpos[w]].y;
      }
    }
  }
  for (int c = 0; c < m; ++c) {  // SPD: no pivoting needed
    for (int r = 0; r < m; ++r) {
      if (r == c || M[r][c] == 0) continue;
      const Rational f = M[r][c] / M[c][c];
      for (int k = c; k < m + 2; ++k) M[r][k] -= f * M[c][k];
    }
  }
  std::vector<Point2q> uv(d.nv);
  for (int v = 0; v < d.nv; ++v)
    uv[v] = bpos[v] >= 0 ? d.buv[bpos[v]]
                         : Point2q{Rational(M[idx[v]][m] / M[idx[v]][idx[v]]), Rational(M[idx[v]][m + 1] / M[idx[v]][idx[v]])};
  return uv;
}
}  // namespace

TEST_CASE("forced refinement converges to the exact Tutte solution (linear, > 30 bits per step)") {
  const DiskMesh d = grid_disk(8, 3, {Point2q{q(0), q(0)}, Point2q{q(1), q(0)}, Point2q{q(1), q(1)}, Point2q{q(0), q(1)}});
  const std::vector<Point2q> exact = exact_tutte(d);
  auto max_error = [&](const TutteResult& r) {
    Rational worst = 0;
    for (int v = 0; v < d.nv; ++v) {
      Rational dx = abs(r.uv[v].x - exact[v].x), dy = abs(r.uv[v].y - exact[v].y);
      if (dx > worst) worst = dx;
      if (dy > worst) worst = dy;
    }
    return worst;
  };
  const Rational e0 = max_error(embed(d));  // the plain double solution
  CHECK(e0 < Rational(1, 1 << 30));
  Rational previous = e0;
  for (int k = 1; k <= 4; ++k) {
    TutteOptions o;
    o.min_iterations = k;
    const TutteResult r = embed(d, o);
    CHECK(r.stats.iterations == k);
    check_embedding(d, r, true);
    const Rational ek = max_error(r);
    // Each step gains at least 30 bits (or hits the exact solution).
    CHECK(ek * (Integer(1) << 30) <= previous);
    previous = ek;
  }
  // The exact fallback reproduces the independent exact solution bit for bit.
  const std::array<Point2q, 3> abc = {Point2q{q(0), q(1)}, Point2q{q(1), q(1)}, Point2q{q(1, 3), q(2)}};
  const DiskMesh f = fan_disk(60, abc);
  TutteOptions o;
  o.max_iterations = 0;
  const TutteResult r = embed(f, o);
  REQUIRE(r.stats.exact_fallback);
  const std::vector<Point2q> ex = exact_tutte(f);
  bool equal = true;
  for (int v = 0; v < f.nv; ++v)
    if (r.uv[v].x != ex[v].x || r.uv[v].y != ex[v].y) equal = false;
  CHECK(equal);
}
