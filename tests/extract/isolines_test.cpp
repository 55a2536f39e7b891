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

#include "../certify/igm_builders.h"
#include "certify/certify.h"
#include "generated_mesh.h"
#include "igm/core/error.h"
#include "igm/extract/isolines.h"
#include "igm/mesh/surface_point.h"
#include "igm/pipeline/pipeline.h"

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

// Extracts, requires the certifier to accept the input, and checks what holds for every output:
// each vertex exactly where it says (its barycentric coordinates give its integer UV, vanish as its
// kind says), the vertices are the test's own grid points once each, every edge id on two sides.
IsolineQuads extract_checked(const IsolineInput& in, const IsolineOptions& options = {}) {
  IsolineResult r = extract_isolines(in, options);
  REQUIRE(r.report.valid());
  REQUIRE(r.quads.has_value());
  const IsolineQuads& q = *r.quads;
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
    if (v.valence != 4) CHECK(v.kind == GridPointKind::Vertex);
    keys.insert(key(on_mesh(in.triangles[v.triangle], w, nullptr)));
  }
  CHECK(keys.size() == q.vertices.size());  // no point twice
  CHECK(keys == brute_force_points(in));    // and every one
  std::vector<int> sides(q.num_edges, 0);
  for (const auto& e : q.quad_edges)
    for (int id : e) ++sides[id];
  for (int n : sides) CHECK(n == 2);
  CHECK(q.stats.max_trace_steps <= q.stats.trace_step_bound);
  return q;
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
