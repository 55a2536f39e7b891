// Tests of the exact isoline extraction from any certified IGM: hand-counted quads of synthetic
// IGMs (the certifier's builders), grid points on vertices, inside edges, inside faces and at
// cones, integer scaling, a nudged seam refused, a trace longer than F triangles, and the
// pipeline's own quads as an oracle (genus 0, 2 and 3).
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "certify/certify.h"
#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/extract/isolines.h"
#include "igm/mesh/surface_point.h"
#include "igm/pipeline/pipeline.h"
#include "igm/smooth/smooth.h"
#include "open_igm.h"

using namespace igm;

namespace {

IsolineInput from_certify(const certify::IgmInput& in) {
  IsolineInput out;
  out.triangles = in.faces;
  for (std::size_t f = 0; f < in.faces.size(); ++f) {
    std::array<Point2q, 3> t;
    for (int i = 0; i < 3; ++i) t[i] = {in.corner_uv[3 * f + i][0], in.corner_uv[3 * f + i][1]};
    out.corner_uv.push_back(t);
  }
  return out;
}

// Every UV times s, plus (dx, dy).
IsolineInput affine(IsolineInput in, const Rational& s, const Rational& dx = 0,
                    const Rational& dy = 0) {
  for (auto& t : in.corner_uv)
    for (Point2q& p : t) {
      p.x = p.x * s + dx;
      p.y = p.y * s + dy;
    }
  return in;
}

std::string key(const SurfacePoint& p) {
  std::string k;
  for (int i = 0; i < 3; ++i) k += std::to_string(p.v[i]) + ":" + to_string(p.w[i]) + " ";
  return k;
}

SurfacePoint on_mesh(const std::array<int, 3>& t, const std::array<Rational, 3>& w,
                     const std::vector<SurfacePoint>* locations) {
  if (!locations)
    return barycentric_point(SurfacePoint::vertex(t[0]), SurfacePoint::vertex(t[1]),
                             SurfacePoint::vertex(t[2]), w);
  return barycentric_point((*locations)[t[0]], (*locations)[t[1]], (*locations)[t[2]], w);
}

// The test's own search for the grid points, independent of the extractor's: every integer point
// of every closed UV triangle (bounding box, three orient2d), as an exact point of the mesh (or of
// the surface the mesh's `locations` lie on): the same point seen from two triangles is one key.
std::set<std::string> brute_force_points(const IsolineInput& in,
                                         const std::vector<SurfacePoint>* locations = nullptr) {
  std::set<std::string> keys;
  for (std::size_t f = 0; f < in.triangles.size(); ++f) {
    const auto& x = in.corner_uv[f];
    Rational lo_x = x[0].x, hi_x = x[0].x, lo_y = x[0].y, hi_y = x[0].y;
    for (const Point2q& p : x) {
      lo_x = std::min(lo_x, p.x), hi_x = std::max(hi_x, p.x);
      lo_y = std::min(lo_y, p.y), hi_y = std::max(hi_y, p.y);
    }
    mpz_class i0, i1, j0, j1;
    mpz_cdiv_q(i0.get_mpz_t(), lo_x.get_num_mpz_t(), lo_x.get_den_mpz_t());
    mpz_fdiv_q(i1.get_mpz_t(), hi_x.get_num_mpz_t(), hi_x.get_den_mpz_t());
    mpz_cdiv_q(j0.get_mpz_t(), lo_y.get_num_mpz_t(), lo_y.get_den_mpz_t());
    mpz_fdiv_q(j1.get_mpz_t(), hi_y.get_num_mpz_t(), hi_y.get_den_mpz_t());
    for (long i = i0.get_si(); i <= i1.get_si(); ++i)
      for (long j = j0.get_si(); j <= j1.get_si(); ++j) {
        const Point2q p{Rational(i), Rational(j)};
        if (orient2d(x[0], x[1], p) == Sign::Negative ||
            orient2d(x[1], x[2], p) == Sign::Negative || orient2d(x[2], x[0], p) == Sign::Negative)
          continue;
        auto area2 = [](const Point2q& a, const Point2q& b, const Point2q& c) {
          Rational r = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
          return r;
        };
        const Rational total = area2(x[0], x[1], x[2]);
        const std::array<Rational, 3> w{Rational(area2(p, x[1], x[2]) / total),
                                        Rational(area2(x[0], p, x[2]) / total),
                                        Rational(area2(x[0], x[1], p) / total)};
        keys.insert(key(on_mesh(in.triangles[f], w, locations)));
      }
  }
  return keys;
}

certify::Report certify_result(const IsolineQuads& q, int genus) {
  certify::QuadInput qin;
  qin.quads = q.quads;
  qin.num_vertices = static_cast<std::int64_t>(q.vertices.size());
  certify::Options o;
  o.expected_genus = genus;
  return certify::certify_quads(qin, o);
}

// The input's boundary, found here from the triangles alone: undirected edges with one face.
std::set<std::pair<int, int>> boundary_edges(const IsolineInput& in) {
  std::map<std::pair<int, int>, int> faces;
  for (const auto& t : in.triangles)
    for (int i = 0; i < 3; ++i) ++faces[std::minmax(t[i], t[(i + 1) % 3])];
  std::set<std::pair<int, int>> edges;
  for (const auto& [e, n] : faces)
    if (n == 1) edges.insert(e);
  return edges;
}

// The total UV length of the input's boundary edges (each axis-parallel: |du| + |dv|), exactly.
Rational boundary_length(const IsolineInput& in) {
  const std::set<std::pair<int, int>> edges = boundary_edges(in);
  Rational length = 0;
  for (std::size_t f = 0; f < in.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i)
      if (edges.count(std::minmax(in.triangles[f][i], in.triangles[f][(i + 1) % 3]))) {
        const Point2q &a = in.corner_uv[f][i], &b = in.corner_uv[f][(i + 1) % 3];
        length += abs(Rational(b.x - a.x)) + abs(Rational(b.y - a.y));
      }
  return length;
}

// Extracts, requires the certifier to accept the input, and checks what holds for every output:
// each vertex exactly where it says (its barycentric coordinates give its integer UV, vanish as its
// kind says), the vertices are the test's own grid points once each, every edge id on two sides
// (on one side: a boundary segment of the quads, between two boundary points; as many as the
// input's boundary is long), boundary points where the input's boundary is; with boundary or
// components allowed, the quads certified with the input's loops and components.
IsolineResult extract_result(const IsolineInput& in, const IsolineOptions& options = {}) {
  IsolineResult r = extract_isolines(in, options);
  REQUIRE(r.report.valid());
  REQUIRE(r.quads.has_value());
  const IsolineQuads& q = *r.quads;
  const std::set<std::pair<int, int>> open = boundary_edges(in);
  std::set<int> open_vertices;
  for (const auto& [a, b] : open) open_vertices.insert(a), open_vertices.insert(b);
  std::set<std::string> keys;
  for (const IsolineQuadVertex& v : q.vertices) {
    const auto& x = in.corner_uv[v.triangle];
    const auto& w = v.barycentric;
    CHECK(w[0] + w[1] + w[2] == 1);
    Rational u = w[0] * x[0].x + w[1] * x[1].x + w[2] * x[2].x,
             vv = w[0] * x[0].y + w[1] * x[1].y + w[2] * x[2].y;
    CHECK(u == Rational(static_cast<long>(v.uv[0])));
    CHECK(vv == Rational(static_cast<long>(v.uv[1])));
    int zeros = 0;
    for (int i = 0; i < 3; ++i) {
      CHECK(sgn(w[i]) >= 0);
      zeros += sgn(w[i]) == 0;
    }
    if (v.kind == GridPointKind::Vertex) CHECK((zeros == 2 && w[v.local] == 1));
    if (v.kind == GridPointKind::Edge) CHECK((zeros == 1 && sgn(w[(v.local + 2) % 3]) == 0));
    if (v.kind == GridPointKind::Face) CHECK(zeros == 0);
    const auto& t = in.triangles[v.triangle];
    const bool on_boundary = (v.kind == GridPointKind::Vertex && open_vertices.count(t[v.local])) ||
                             (v.kind == GridPointKind::Edge &&
                              open.count(std::minmax(t[v.local], t[(v.local + 1) % 3])));
    CHECK(v.boundary == on_boundary);
    if (v.valence != (v.boundary ? 3 : 4)) CHECK(v.kind == GridPointKind::Vertex);
    keys.insert(key(on_mesh(in.triangles[v.triangle], w, nullptr)));
  }
  CHECK(keys.size() == q.vertices.size());  // no point twice
  CHECK(keys == brute_force_points(in));    // and every one
  std::vector<int> sides(q.num_edges, 0);
  std::vector<std::array<int, 2>> ends(q.num_edges);
  for (std::size_t f = 0; f < q.quads.size(); ++f)
    for (int k = 0; k < 4; ++k) {
      ++sides[q.quad_edges[f][k]];
      ends[q.quad_edges[f][k]] = {q.quads[f][k], q.quads[f][(k + 1) % 4]};
    }
  int boundary_segments = 0;
  for (int e = 0; e < q.num_edges; ++e) {
    CHECK((sides[e] == 2 || (sides[e] == 1 && options.allow_boundary)));
    if (sides[e] != 1) continue;
    ++boundary_segments;
    CHECK(q.vertices[ends[e][0]].boundary);
    CHECK(q.vertices[ends[e][1]].boundary);
  }
  CHECK(Rational(boundary_segments) == boundary_length(in));
  CHECK(q.stats.max_trace_steps <= q.stats.trace_step_bound);
  if (options.allow_boundary || options.allow_components) {
    const certify::Report quads = certify_isoline_quads(r, options);
    CHECK(quads.valid());
    CHECK(quads.boundary_loops == r.report.boundary_loops);
    CHECK(q.boundary_loops == *r.report.boundary_loops);
  }
  return r;
}

IsolineQuads extract_checked(const IsolineInput& in, const IsolineOptions& options = {}) {
  return *extract_result(in, options).quads;
}

// A quad up to rotation: its lexicographically smallest rotation (ids may repeat at coarse grids).
std::array<int, 4> canonical(std::array<int, 4> q) {
  std::array<int, 4> best = q;
  for (int k = 1; k < 4; ++k) {
    std::rotate(q.begin(), q.begin() + 1, q.end());
    best = std::min(best, q);
  }
  return best;
}

// The mesh vertex a grid point on a vertex is.
int mesh_vertex(const IsolineInput& in, const IsolineQuadVertex& v) {
  REQUIRE(v.kind == GridPointKind::Vertex);
  return in.triangles[v.triangle][v.local];
}

}  // namespace

TEST_CASE(
    "isolines: the n x n torus with the grid on its vertices gives its n^2 cells, "
    "counter-clockwise") {
  for (int n : {3, 4}) {
    CAPTURE(n);
    const IsolineInput in = from_certify(certify_test::torus(n));
    const IsolineQuads q = extract_checked(in);
    CHECK(q.quads.size() == std::size_t(n * n));
    CHECK(q.vertices.size() == std::size_t(n * n));
    CHECK(q.num_edges == 2 * n * n);
    CHECK(q.genus == 1);
    CHECK(q.stats.grid_points_on_vertices == n * n);
    CHECK(q.stats.grid_points_on_edges == 0);
    CHECK(q.stats.grid_points_in_faces == 0);
    CHECK(q.stats.cones == 0);
    // vertex (i, j) of the builder has id i + n j; cell (i, j) is (i,j) (i+1,j) (i+1,j+1) (i,j+1)
    std::multiset<std::array<int, 4>> expected, got;
    auto id = [n](int i, int j) { return (i % n) + n * (j % n); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        expected.insert(canonical({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)}));
    for (const auto& quad : q.quads) {
      std::array<int, 4> m;
      for (int k = 0; k < 4; ++k) m[k] = mesh_vertex(in, q.vertices[quad[k]]);
      got.insert(canonical(m));
    }
    CHECK(got == expected);
    CHECK(certify_result(q, 1).valid());
  }
}

TEST_CASE("isolines: grid points inside horizontal edges, inside diagonal edges and inside faces") {
  const int n = 4;
  const IsolineInput torus = from_certify(certify_test::torus(n));
  struct Case {
    Rational dx, dy;
    GridPointKind kind;
    int side;  // the side of the cell's triangle the points lie on (-1: inside)
  };
  // vertex (i, j) at (i + dx, j + dy): the integer point (i + 1, j) or (i + 1, j + 1) lies ...
  const Case cases[] = {
      {Rational(1, 2), 0, GridPointKind::Edge, 0},                // on the lower side
      {Rational(1, 2), Rational(1, 2), GridPointKind::Edge, -1},  // on the diagonal
      {Rational(1, 4), Rational(1, 2), GridPointKind::Face, -1}};
  for (const Case& c : cases) {
    CAPTURE(to_string(c.dx));
    CAPTURE(to_string(c.dy));
    const IsolineQuads q = extract_checked(affine(torus, 1, c.dx, c.dy));
    CHECK(q.quads.size() == std::size_t(n * n));
    CHECK(q.vertices.size() == std::size_t(n * n));
    CHECK(q.stats.grid_points_on_vertices == 0);
    CHECK(q.stats.grid_points_on_edges == (c.kind == GridPointKind::Edge ? n * n : 0));
    CHECK(q.stats.grid_points_in_faces == (c.kind == GridPointKind::Face ? n * n : 0));
    for (const IsolineQuadVertex& v : q.vertices) {
      CHECK(v.kind == c.kind);
      CHECK(v.valence == 4);
    }
    // Horizontal isolines run through the vertices when dy == 0 (and vertical ones never do).
    CHECK((q.stats.vertex_crossings > 0) == (c.dy == 0));
    CHECK(certify_result(q, 1).valid());
  }
}

TEST_CASE(
    "isolines: cones on grid points: the cube's 8 corners of valence 3, the pillow's 4 of valence "
    "2") {
  for (int m : {1, 2, 3}) {
    CAPTURE(m);
    const IsolineQuads cube = extract_checked(from_certify(certify_test::cube(m)));
    CHECK(cube.quads.size() == std::size_t(6 * m * m));
    CHECK(cube.vertices.size() == std::size_t(6 * m * m + 2));
    CHECK(cube.stats.cones == 8);
    CHECK(cube.genus == 0);
    int three = 0;
    for (const IsolineQuadVertex& v : cube.vertices) three += v.valence == 3;
    CHECK(three == 8);
    CHECK(certify_result(cube, 0).valid());

    const IsolineQuads pillow = extract_checked(from_certify(certify_test::pillow(m)));
    CHECK(pillow.quads.size() == std::size_t(2 * m * m));
    CHECK(pillow.vertices.size() == std::size_t((m + 1) * (m + 1) + (m - 1) * (m - 1)));
    CHECK(pillow.stats.cones == 4);
    for (const IsolineQuadVertex& v : pillow.vertices) CHECK((v.valence == 4 || v.valence == 2));
    CHECK(certify_result(pillow, 0).valid());
  }
}

TEST_CASE(
    "isolines: charts rotated by +-90 degrees, scaled by 2 and shifted by a half: points inside "
    "edges and faces") {
  const IsolineInput rotated = from_certify(certify_test::rotated_chart_torus(7));
  const IsolineQuads q1 = extract_checked(rotated);
  CHECK(q1.quads.size() == 49u);
  CHECK(certify_result(q1, 1).valid());
  // Each 2 x 2 cell, its lower-left corner at a half-integer point, holds 4 integer points: the two
  // at offsets (1/2, 1/2) and (3/2, 3/2) (or on the other diagonal in a rotated chart) on its
  // diagonal edge, the other two inside its triangles.
  const IsolineQuads q2 = extract_checked(affine(rotated, 2, Rational(1, 2), Rational(1, 2)));
  CHECK(q2.quads.size() == 196u);
  CHECK(q2.stats.grid_points_on_edges == 98);
  CHECK(q2.stats.grid_points_in_faces == 98);
  CHECK(q2.stats.grid_points_on_vertices == 0);
  CHECK(certify_result(q2, 1).valid());
}

TEST_CASE("isolines: an IGM scaled by an integer k has k^2 times the quads") {
  const IsolineInput inputs[] = {
      from_certify(certify_test::torus(3)), from_certify(certify_test::cube(1)),
      from_certify(certify_test::pillow(2)), from_certify(certify_test::rotated_chart_torus(7))};
  const int genus[] = {1, 0, 0, 1};
  for (int i = 0; i < 4; ++i) {
    CAPTURE(i);
    const std::size_t base = extract_checked(inputs[i]).quads.size();
    for (int k : {2, 3, 5}) {
      CAPTURE(k);
      const IsolineQuads q = extract_checked(affine(inputs[i], k));
      CHECK(q.quads.size() == std::size_t(k * k) * base);
      CHECK(q.genus == genus[i]);
      CHECK(certify_result(q, genus[i]).valid());
    }
  }
}

TEST_CASE(
    "isolines: one corner UV nudged by 1/1000 is refused with the certifier's witness, no quads") {
  certify::IgmInput torus = certify_test::torus(4);
  const int f = 5;  // cell (2, 0), upper triangle: corners (2,0) (3,1) (2,1)
  torus.corner_uv[3 * f + 1][0] += mpq_class(1, 1000);
  const IsolineResult r = extract_isolines(from_certify(torus));
  CHECK_FALSE(r.report.valid());
  CHECK_FALSE(r.quads.has_value());
  const certify::CheckResult* seams = r.report.check(3);
  REQUIRE(seams != nullptr);
  CHECK(seams->status == certify::Status::Fail);
  // The nudged corner is vertex (3, 1) = 7 of face 5; its sides there join it to (2, 0) = 2 and (2,
  // 1) = 6.
  CHECK(certify_test::has_edge_witness(*seams, 2, 7));
  CHECK(certify_test::has_edge_witness(*seams, 6, 7));
}

TEST_CASE("isolines: unreadable input and bad options") {
  IsolineInput in = from_certify(certify_test::torus(3));
  in.corner_uv.pop_back();
  const IsolineResult r = extract_isolines(in);
  CHECK(r.report.verdict == certify::Verdict::Unreadable);
  CHECK_FALSE(r.quads.has_value());
  IsolineOptions o;
  o.max_grid_work = 0;
  CHECK_THROWS_AS(extract_isolines(from_certify(certify_test::torus(3)), o), Error);
  // The grid search's work bound: the 3 x 3 torus has 9 rows and 9 points... times 25 scaled by 5.
  o.max_grid_work = 200;
  CHECK(extract_isolines(from_certify(certify_test::torus(3)), o).quads.has_value());
  try {
    extract_isolines(affine(from_certify(certify_test::torus(3)), 5), o);
    FAIL("the work bound did not stop the search");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::TooLarge);
  }
  // A valid IGM translated by 2^61: beyond the 64-bit grid coordinates, refused by name.
  Rational far = 1;
  mpq_mul_2exp(far.get_mpq_t(), far.get_mpq_t(), 61);
  try {
    extract_isolines(affine(from_certify(certify_test::torus(3)), 1, far, 0));
    FAIL("UVs beyond 2^60 accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::TooLarge);
  }
}

TEST_CASE(
    "isolines: 3D positions are the exact points rounded, the input's own positions on vertices") {
  IsolineInput in = affine(from_certify(certify_test::torus(4)), 1, Rational(1, 2), 0);
  for (int v = 0; v < 16; ++v) in.positions.push_back({double(v % 4), double(v / 4), 1.0});
  const IsolineQuads q = extract_checked(in);
  REQUIRE(q.positions.size() == q.vertices.size());
  for (std::size_t p = 0; p < q.vertices.size(); ++p) {
    // inside the lower side of a cell, halfway: the mean of its two ends' positions (exact in
    // doubles)
    const IsolineQuadVertex& v = q.vertices[p];
    const int a = in.triangles[v.triangle][v.local],
              b = in.triangles[v.triangle][(v.local + 1) % 3];
    CHECK(v.barycentric[v.local] == Rational(1, 2));
    CHECK(q.positions[p].x == (in.positions[a].x + in.positions[b].x) / 2);
    CHECK(q.positions[p].y == (in.positions[a].y + in.positions[b].y) / 2);
    CHECK(q.positions[p].z == 1.0);
  }
  IsolineInput grid = from_certify(certify_test::torus(3));
  for (int v = 0; v < 9; ++v) grid.positions.push_back({0.1 * v, -0.3 * v, 7.0 / (v + 1)});
  const IsolineQuads on_vertices = extract_checked(grid);
  REQUIRE(on_vertices.positions.size() == 9u);
  for (std::size_t p = 0; p < 9; ++p) {
    const Vec3d& a = on_vertices.positions[p];
    const Vec3d& b = grid.positions[mesh_vertex(grid, on_vertices.vertices[p])];
    CHECK((a.x == b.x && a.y == b.y && a.z == b.z));
  }
}

namespace {

// The torus R^2 / 3Z^2 triangulated by the lattice (1/2)Z^2 in the skewed basis a = (1/2, 0),
// b = (m/2, 1/2): cell (i, j) (0 <= i, j < 6) has corners p, p + a, p + a + b, p + b with
// p = i a + j b, split along p -> p + a + b; vertex (u/2, w/2) has id (u mod 6) + 6 (w mod 6).
// 36 vertices, 72 slivers m/2 long; the grid points are the 9 integer points, all on vertices.
IsolineInput skewed_torus(int m) {
  IsolineInput in;
  auto id = [](int u, int w) { return (u % 6 + 6) % 6 + 6 * ((w % 6 + 6) % 6); };
  auto at = [](int u, int w) { return Point2q{Rational(u, 2), Rational(w, 2)}; };
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 6; ++i) {
      const int u = i + m * j, w = j;
      in.triangles.push_back({id(u, w), id(u + 1, w), id(u + 1 + m, w + 1)});
      in.corner_uv.push_back({at(u, w), at(u + 1, w), at(u + 1 + m, w + 1)});
      in.triangles.push_back({id(u, w), id(u + 1 + m, w + 1), id(u + m, w + 1)});
      in.corner_uv.push_back({at(u, w), at(u + 1 + m, w + 1), at(u + m, w + 1)});
    }
  for (auto& t : in.corner_uv)
    for (Point2q& p : t) p.x.canonicalize(), p.y.canonicalize();
  return in;
}

}  // namespace

TEST_CASE("isolines: a trace may cross more than F triangles (slivers), within the bound C") {
  const IsolineInput in = skewed_torus(30);
  const IsolineQuads q = extract_checked(in);
  CHECK(q.quads.size() == 9u);
  CHECK(q.stats.grid_points_on_vertices == 9);
  CHECK(q.stats.max_trace_steps > static_cast<std::int64_t>(in.triangles.size()));  // 120 > 72
  CHECK(q.stats.vertex_crossings > 0);
  CHECK(certify_result(q, 1).valid());
}

namespace {

// The pipeline as an oracle: its unsmoothed IGM is on its quad mesh's grid (one UV unit per quad)
// and with structured_extraction its quads are the layout's rectangles (or the pillowcase's cells),
// so the extractor must give the pipeline's quads, at the same exact points of the input surface
// (QuadMesh::locations), under a matching of the vertices by their exact location. The test's own
// grid search (brute_force_points) gives the set G of exact surface points of the IGM's integer
// points; the extractor's vertices must be G, once each.
void check_against_pipeline(const ValidMesh& mesh, int N) {
  PipelineOptions o;
  o.layout = LayoutKind::Spread;  // the topological layout (the field one has its own tests)
  o.resolution = N;
  o.quality = false;
  o.smooth = false;
  o.structured_extraction = true;  // the oracle: the quads from the layout's rectangles
  const PipelineResult r = compute_igm(mesh, o);
  INFO("genus " << mesh.genus << ", resolution " << N);
  REQUIRE(r.certified());
  IsolineInput in;
  in.triangles = r.igm.triangles;
  in.corner_uv = r.igm.corner_uv;
  const IsolineQuads q = extract_checked(in);
  CHECK(q.genus == mesh.genus);
  CHECK(q.quads.size() == r.quads.quads.size());
  CHECK(q.quads.size() == std::size_t(r.stats.layout_quads) * N * N);
  CHECK(certify_result(q, mesh.genus).valid());

  const std::set<std::string> grid = brute_force_points(in, &r.igm.locations);
  std::map<std::string, int> mine;
  for (std::size_t v = 0; v < q.vertices.size(); ++v)
    mine.emplace(key(on_mesh(in.triangles[q.vertices[v].triangle], q.vertices[v].barycentric, &r.igm.locations)),
                 static_cast<int>(v));
  REQUIRE(mine.size() == q.vertices.size());
  std::set<std::string> mine_keys;
  for (const auto& [k, v] : mine) mine_keys.insert(k);
  CHECK(mine_keys == grid);
  REQUIRE(r.quads.locations.size() == q.vertices.size());
  std::vector<int> match(r.quads.locations.size(), -1);
  std::set<int> matched;
  for (std::size_t u = 0; u < match.size(); ++u) {
    const auto it = mine.find(key(r.quads.locations[u]));
    REQUIRE(it != mine.end());
    match[u] = it->second;
    matched.insert(it->second);
  }
  CHECK(matched.size() == match.size());
  std::multiset<std::array<int, 4>> theirs, ours;
  for (const auto& quad : r.quads.quads)
    theirs.insert(canonical({match[quad[0]], match[quad[1]], match[quad[2]], match[quad[3]]}));
  for (const auto& quad : q.quads) ours.insert(canonical(quad));
  CHECK(ours == theirs);
}

}  // namespace

TEST_CASE(
    "isolines: the pipeline's genus-2 and genus-3 IGMs give the pipeline's quads at the same exact "
    "points") {
  check_against_pipeline(igm_test::generated_mesh(2, 600, 7), 3);
  check_against_pipeline(igm_test::generated_mesh(3, 900, 8), 4);
  check_against_pipeline(igm_test::generated_mesh(2, 600, 7), 1);  // the spread layout: one quad per layout quad
}

TEST_CASE("isolines: the pipeline's genus-0 IGM (four pi-cones) gives the pipeline's quads") {
  const ValidMesh sphere = igm_test::generated_mesh(0, 600, 3);
  check_against_pipeline(sphere, 1);
  check_against_pipeline(sphere, 3);
}

// ---- surfaces with boundary and several components ----

namespace {

IsolineOptions open_surfaces() {
  IsolineOptions o;
  o.allow_boundary = true;
  o.allow_components = true;
  return o;
}

// Per valence, the grid points on the boundary.
std::map<int, int> boundary_valences(const IsolineQuads& q) {
  std::map<int, int> h;
  for (const IsolineQuadVertex& v : q.vertices)
    if (v.boundary) ++h[v.valence];
  return h;
}

}  // namespace

TEST_CASE("isolines with boundary: the n x n disk gives its n^2 cells, corners of valence 2") {
  for (int n : {1, 2, 3}) {
    CAPTURE(n);
    const certify_test::GridPatch g = certify_test::square_disk(n);
    const IsolineInput in = from_certify(g.igm);
    const IsolineQuads q = extract_checked(in, open_surfaces());
    CHECK(q.quads.size() == std::size_t(n * n));
    CHECK(q.vertices.size() == std::size_t((n + 1) * (n + 1)));
    CHECK(q.num_edges == 2 * n * (n + 1));
    CHECK(q.genus == 0);
    CHECK(q.boundary_loops == 1);
    CHECK(q.stats.grid_points_on_vertices == (n + 1) * (n + 1));
    CHECK(q.stats.grid_points_on_edges + q.stats.grid_points_in_faces == 0);
    CHECK(q.stats.grid_points_on_boundary == 4 * n);
    CHECK(q.stats.boundary_corners == 4);
    CHECK(q.stats.cones == 0);
    std::map<int, std::pair<int, int>> at;  // mesh vertex -> (i, j)
    for (const auto& [k, v] : g.ids) at[v] = {k[0], k[1]};
    for (const IsolineQuadVertex& v : q.vertices) {
      const auto [i, j] = at.at(mesh_vertex(in, v));
      const int sides = (i == 0 || i == n) + (j == 0 || j == n);
      CHECK(v.valence == 4 - sides);
      CHECK(v.boundary == (sides > 0));
    }
    std::multiset<std::array<int, 4>> expected, got;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        expected.insert(
            canonical({g.id(i, j), g.id(i + 1, j), g.id(i + 1, j + 1), g.id(i, j + 1)}));
    for (const auto& quad : q.quads) {
      std::array<int, 4> m;
      for (int k = 0; k < 4; ++k) m[k] = mesh_vertex(in, q.vertices[quad[k]]);
      got.insert(canonical(m));
    }
    CHECK(got == expected);
  }
}

TEST_CASE("isolines with boundary: grid points inside boundary edges, inside edges and faces") {
  // The 4 x 4 disk scaled by 3/4: [0, 3]^2 with vertices at multiples of 3/4. Its 16 integer
  // points: the 4 corners on vertices; (1, 0), (2, 0), ... inside the 8 boundary edges they meet;
  // (1, 1) and (2, 2) inside diagonals, (1, 2) and (2, 1) inside triangles.
  const IsolineInput in = affine(from_certify(certify_test::square_disk(4).igm), Rational(3, 4));
  const IsolineQuads q = extract_checked(in, open_surfaces());
  CHECK(q.quads.size() == 9u);
  CHECK(q.vertices.size() == 16u);
  CHECK(q.stats.grid_points_on_vertices == 4);
  CHECK(q.stats.grid_points_on_edges == 10);
  CHECK(q.stats.grid_points_in_faces == 2);
  CHECK(q.stats.grid_points_on_boundary == 12);
  CHECK(q.stats.boundary_corners == 4);
  int inside_boundary_edges = 0;
  for (const IsolineQuadVertex& v : q.vertices)
    inside_boundary_edges += v.boundary && v.kind == GridPointKind::Edge;
  CHECK(inside_boundary_edges == 8);
  CHECK(boundary_valences(q) == std::map<int, int>{{2, 4}, {3, 8}});
  // The unit segments along the boundary pass through its vertices at 3/4, 3/2 and 9/4 of each
  // side (one each), traced from both ends: forwards and backwards through 12 fans. No interior
  // vertex (3i/4, 3j/4), 0 < i, j < 4, is on an integer line.
  CHECK(q.stats.vertex_crossings == 24);
}

TEST_CASE("isolines with boundary: cylinders, two loops of straight boundary") {
  for (const auto& [n, m] : {std::pair{3, 1}, std::pair{4, 2}, std::pair{5, 3}}) {
    CAPTURE(n);
    CAPTURE(m);
    const IsolineQuads q = extract_checked(from_certify(certify_test::cylinder(n, m).igm),
                                           open_surfaces());
    CHECK(q.quads.size() == std::size_t(n * m));
    CHECK(q.vertices.size() == std::size_t(n * (m + 1)));
    CHECK(q.genus == 0);
    CHECK(q.boundary_loops == 2);
    CHECK(boundary_valences(q) == std::map<int, int>{{3, 2 * n}});
    CHECK(q.stats.boundary_corners == 0);
  }
}

TEST_CASE("isolines with boundary: L-shapes (a reflex corner of valence 4) and a slit (tip 5)") {
  for (int n : {1, 2}) {
    CAPTURE(n);
    const IsolineQuads q = extract_checked(from_certify(certify_test::l_shape(n).igm),
                                           open_surfaces());
    CHECK(q.quads.size() == std::size_t(3 * n * n));
    CHECK(q.vertices.size() == std::size_t((2 * n + 1) * (2 * n + 1) - n * n));
    CHECK(q.boundary_loops == 1);
    CHECK(boundary_valences(q) == std::map<int, int>{{2, 5}, {3, 8 * n - 6}, {4, 1}});
  }
  // [0, 4]^2 cut along x = 2 up to y = 2: the points (2, 0) and (2, 1) twice.
  const certify_test::GridPatch g = certify_test::slit_square(4, 2, 2);
  const IsolineInput in = from_certify(g.igm);
  const IsolineQuads q = extract_checked(in, open_surfaces());
  CHECK(q.quads.size() == 16u);
  CHECK(q.vertices.size() == 27u);
  CHECK(q.boundary_loops == 1);
  CHECK(boundary_valences(q) == std::map<int, int>{{2, 6}, {3, 13}, {5, 1}});
  for (const IsolineQuadVertex& v : q.vertices)
    if (v.valence == 5) CHECK(mesh_vertex(in, v) == g.id(2, 2));
}

TEST_CASE("isolines with boundary: interior cones and boundary corners, an open cube") {
  // The pillow 3 x 3 without one front cell: a disk, 4 cones of valence 2, a square hole whose
  // 4 corners have boundary angle 3 pi/2 (valence 4).
  const IsolineQuads pillow =
      extract_checked(from_certify(certify_test::pillow_with_hole(3, 1, 1)), open_surfaces());
  CHECK(pillow.quads.size() == 17u);
  CHECK(pillow.vertices.size() == 20u);
  CHECK(pillow.stats.cones == 4);
  CHECK(pillow.stats.boundary_corners == 4);
  CHECK(boundary_valences(pillow) == std::map<int, int>{{4, 4}});
  for (const IsolineQuadVertex& v : pillow.vertices)
    if (!v.boundary) CHECK((v.valence == 4 || v.valence == 2));
  // The cube 2 x 2 x 2 without its bottom: the rim is straight (two quarter angles at its
  // corners), the 4 top corners are cones of valence 3.
  const IsolineQuads cube = extract_checked(from_certify(certify_test::cube(2, 63 & ~(1 << 4))),
                                            open_surfaces());
  CHECK(cube.quads.size() == 20u);
  CHECK(cube.vertices.size() == 25u);
  CHECK(cube.stats.cones == 4);
  CHECK(cube.stats.boundary_corners == 0);
  CHECK(boundary_valences(cube) == std::map<int, int>{{3, 8}});
}

TEST_CASE("isolines of several components: a disk and a torus, two tori") {
  const certify::IgmInput disk = certify_test::square_disk(2).igm;
  const IsolineQuads q =
      extract_checked(from_certify(certify_test::disjoint_union(disk, certify_test::torus(3))),
                      open_surfaces());
  CHECK(q.quads.size() == 4u + 9u);
  CHECK(q.vertices.size() == 9u + 9u);
  CHECK(q.genus == 1);
  CHECK(q.boundary_loops == 1);
  IsolineOptions components;
  components.allow_components = true;
  const IsolineInput tori =
      from_certify(certify_test::disjoint_union(certify_test::torus(3), certify_test::torus(4)));
  const IsolineResult r = extract_result(tori, components);
  CHECK(r.quads->quads.size() == 9u + 16u);
  CHECK(r.quads->genus == 2);
  CHECK(r.quads->boundary_loops == 0);
  const certify::Report report = certify_isoline_quads(r, components);
  CHECK(report.components.size() == 2u);
  CHECK(report.valid());
  // Refused without allow_components: check 1, no quads.
  const IsolineResult refused = extract_isolines(tori);
  CHECK_FALSE(refused.report.valid());
  CHECK_FALSE(refused.quads.has_value());
  CHECK(refused.report.check(1)->status == certify::Status::Fail);
}

TEST_CASE("isolines with boundary: an IGM scaled by an integer k has k^2 times the quads") {
  const IsolineInput inputs[] = {
      from_certify(certify_test::square_disk(2).igm),
      from_certify(certify_test::cylinder(3, 1).igm),
      from_certify(certify_test::l_shape(1).igm),
      from_certify(certify_test::slit_square(4, 2, 2).igm),
      from_certify(certify_test::pillow_with_hole(3, 1, 1)),
      from_certify(certify_test::disjoint_union(certify_test::square_disk(1).igm,
                                                certify_test::torus(3)))};
  const int loops[] = {1, 2, 1, 1, 1, 1};
  for (int i = 0; i < 6; ++i) {
    CAPTURE(i);
    const IsolineQuads base = extract_checked(inputs[i], open_surfaces());
    CHECK(base.boundary_loops == loops[i]);
    for (int k : {2, 3}) {
      CAPTURE(k);
      const IsolineQuads q = extract_checked(affine(inputs[i], k), open_surfaces());
      CHECK(q.quads.size() == std::size_t(k * k) * base.quads.size());
      CHECK(q.boundary_loops == loops[i]);
      CHECK(q.stats.grid_points_on_boundary == k * base.stats.grid_points_on_boundary);
    }
  }
}

TEST_CASE(
    "isolines with boundary: refused without allow_boundary, or with a boundary edge off its "
    "isoline") {
  certify_test::GridPatch g = certify_test::square_disk(3);
  const IsolineResult closed_only = extract_isolines(from_certify(g.igm));
  CHECK_FALSE(closed_only.quads.has_value());
  CHECK(closed_only.report.check(1)->status == certify::Status::Fail);
  // Vertex (1, 0) moved up by 1/10: its triangles stay positive, its boundary edges leave v = 0.
  const int v = g.id(1, 0);
  certify_test::move_vertex(g.igm, v, certify_test::uv(1, mpq_class(1, 10)));
  const IsolineResult r = extract_isolines(from_certify(g.igm), open_surfaces());
  CHECK_FALSE(r.report.valid());
  CHECK_FALSE(r.quads.has_value());
  const certify::CheckResult* seams = r.report.check(3);
  REQUIRE(seams != nullptr);
  CHECK(seams->status == certify::Status::Fail);
  CHECK(seams->count("boundary_edges_off_isoline") == 2);
  CHECK(certify_test::has_edge_witness(*seams, g.id(0, 0), v));
  CHECK(certify_test::has_edge_witness(*seams, v, g.id(2, 0)));
  CHECK_THROWS_AS(certify_isoline_quads(r), Error);
}

TEST_CASE("isolines with boundary: smoothed open IGMs keep their quad counts") {
  // Smoothing moves no corner and slides boundary vertices along their isolines: the UV area and
  // the boundary's length stay, so do the numbers of quads and of boundary grid points; the grid
  // points now lie inside edges and triangles.
  const IgmMesh inputs[] = {igm_test::tube(8, 3),
                            igm_test::lifted(certify_test::l_shape(3).igm, igm_test::bumped),
                            igm_test::inflated_pillow_with_hole(4, 1, 2),
                            igm_test::disk_and_torus(3, 4)};
  for (const IgmMesh& igm : inputs) {
    IsolineInput before;
    before.triangles = igm.triangles;
    before.corner_uv = igm.corner_uv;
    const IsolineQuads q0 = extract_checked(before, open_surfaces());
    SmoothOptions so;
    so.max_iterations = 10;
    IsolineInput after = before;
    after.corner_uv = smooth_igm(igm_test::perturbed(igm, 20, 9), so).corner_uv;
    const IsolineQuads q1 = extract_checked(after, open_surfaces());
    CHECK(q1.quads.size() == q0.quads.size());
    CHECK(q1.boundary_loops == q0.boundary_loops);
    CHECK(q1.stats.grid_points_on_boundary == q0.stats.grid_points_on_boundary);
    CHECK(q1.stats.boundary_corners == q0.stats.boundary_corners);
    CHECK(q1.stats.grid_points_in_faces > 0);
  }
}
