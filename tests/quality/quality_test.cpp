#include "igm/quality/quality.h"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "error_kind.h"
#include "igm/core/error.h"

using namespace igm;
using igm_test::kind_of;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const double kPi = std::acos(-1.0);

struct QuadMesh {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 4>> quads;
};

struct TriangleMesh {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 3>> triangles;
};

// The unit cube [0,1]^3: vertex i + 2j + 4k at (i, j, k); quads counter-clockwise from outside.
QuadMesh unit_cube() {
  QuadMesh m;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) m.positions.push_back({double(i), double(j), double(k)});
  m.quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}

// Each quad split along p0-p2.
TriangleMesh triangulated(const QuadMesh& q) {
  TriangleMesh t{q.positions, {}};
  for (const auto& f : q.quads) {
    t.triangles.push_back({f[0], f[1], f[2]});
    t.triangles.push_back({f[0], f[2], f[3]});
  }
  return t;
}

// One quad or a row of axis-aligned quads in the plane z = z0.
QuadMesh planar(const std::vector<std::array<Vec3d, 4>>& quads) {
  QuadMesh m;
  for (const auto& q : quads) {
    const int first = static_cast<int>(m.positions.size());
    m.positions.insert(m.positions.end(), q.begin(), q.end());
    m.quads.push_back({first, first + 1, first + 2, first + 3});
  }
  return m;
}

// The rectangle [x0, x1] x [y0, y1] at height z, counter-clockwise seen from +z.
std::array<Vec3d, 4> rectangle(double x0, double x1, double y0, double y1, double z = 0) {
  return {{{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}};
}

QuadQuality measure(const QuadMesh& q, const TriangleMesh& input, bool distance = false) {
  QuadQualityOptions o;
  o.distance = distance;
  return measure_quads(q.positions, q.quads, input.positions, input.triangles, o);
}

}  // namespace

TEST_CASE("weighted_quantiles: the smallest value whose weight up to it reaches q of the total") {
  // Sorted: 1 (weight 1), 2 (2), 3 (4), 4 (3); cumulative 1, 3, 7, 10.
  const std::vector<double> values = {3, 1, 4, 2}, weights = {4, 1, 3, 2};
  const std::vector<double> q =
      weighted_quantiles(values, weights, {0, 0.1, 0.3, 0.31, 0.5, 0.7, 0.71, 1});
  CHECK(q == std::vector<double>{1, 1, 2, 3, 3, 3, 4, 4});  // 0.3: cumulative 3 >= 3 reaches it
  // A value of zero weight at the top is never reached: the weight up to 1 is already the total.
  CHECK(weighted_quantiles({5, 1}, {0, 1}, {0.5, 1}) == std::vector<double>{1, 1});
  CHECK(weighted_quantiles({}, {}, {0.5, 0.9}) == std::vector<double>{0, 0});
  // Unit weights: the ceil(q n)-th smallest.
  CHECK(quantiles({5, 1, 4, 2, 3}, {0.05, 0.2, 0.5, 0.9, 1}) == std::vector<double>{1, 1, 3, 5, 5});
  CHECK(quantiles({5, 1, 4, 2}, {0.5, 0.75, 0.76}) == std::vector<double>{2, 4, 5});
  CHECK(kind_of([] { weighted_quantiles({1, 2}, {1}, {0.5}); }) == ErrorKind::InvalidArgument);
  CHECK(kind_of([] {
          weighted_quantiles({1, std::nan("")}, {1, 1}, {0.5});
        }) == ErrorKind::InvalidArgument);
  CHECK(kind_of([] { weighted_quantiles({1, 2}, {1, -1}, {0.5}); }) == ErrorKind::InvalidArgument);
  CHECK(kind_of([] {
          weighted_quantiles({1, 2}, {1, kInf}, {0.5});
        }) == ErrorKind::InvalidArgument);
  // An infinite value is ordered last.
  CHECK(quantiles({kInf, 1, 2}, {0.5, 1}) == std::vector<double>{2, kInf});
}

TEST_CASE("measure_quads: irregular vertices are interior ones of valence other than 4") {
  // The cube without one face: the four corners of the missing face are on the boundary (left
  // out), the other four interior of valence 3.
  QuadMesh open = unit_cube();
  open.quads.pop_back();
  const QuadQuality q = measure(open, triangulated(open), false);
  CHECK(q.irregular_vertices == 4);
  CHECK(q.max_valence == 3);
  // A 2 x 2 grid: one interior vertex of valence 4, nothing irregular.
  QuadMesh grid;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) grid.positions.push_back({double(i), double(j), 0});
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) grid.quads.push_back({3 * j + i, 3 * j + i + 1, 3 * j + i + 4, 3 * j + i + 3});
  const QuadQuality g = measure(grid, triangulated(grid), false);
  CHECK(g.irregular_vertices == 0);
  CHECK(g.max_valence == 4);
}

TEST_CASE("measure_quads: the unit cube against its triangulation is perfect") {
  const QuadMesh cube = unit_cube();
  const QuadQuality q = measure(cube, triangulated(cube), true);
  CHECK(q.quads == 6);
  CHECK(q.vertices == 8);
  CHECK(q.degenerate == 0);
  CHECK(q.valence == std::map<int, int>{{3, 8}});
  CHECK(q.irregular_vertices == 8);  // every corner: closed, valence 3
  CHECK(q.max_valence == 3);
  CHECK(q.sj_min == 1);
  CHECK(q.sj_p5 == 1);
  CHECK(q.sj_median == 1);
  CHECK(q.sj_below_half == 0);
  CHECK(q.sj_nonpositive == 0);
  CHECK(q.angle_deviation_median == 0);
  CHECK(q.angle_deviation_p95 == 0);
  CHECK(q.area_p95_over_p5 == 1);
  CHECK(q.area_ratio == 1);
  CHECK(q.smallest_half_area == 0.5);
  CHECK(q.distance_measured);
  // 8 vertices + 12 edge midpoints + 6 centres; 8 vertices + 12 centroids. Every sample lies on
  // the other surface; the bound allows rounding (centroids at thirds), the values are exactly 0.
  CHECK(q.distance_samples_quads == 26);
  CHECK(q.distance_samples_input == 20);
  CHECK(q.distance_max <= 1e-15);
  CHECK(q.distance_p99 <= 1e-15);
}

TEST_CASE("measure_quads: scaled Jacobian and angle deviation of a sheared parallelogram") {
  for (double s : {0.5, 1.0, 3.0}) {
    // (0,0,0), (1,0,0), (1+s,1,0), (s,1,0): every corner has SJ 1/sqrt(1+s^2) and angle 90 -+ atan
    // s.
    const QuadMesh p = planar({{{{0, 0, 0}, {1, 0, 0}, {1 + s, 1, 0}, {s, 1, 0}}}});
    const QuadQuality q = measure(p, triangulated(p));
    INFO("s = " << s);
    CHECK(q.sj_min == doctest::Approx(1 / std::sqrt(1 + s * s)).epsilon(1e-14));
    CHECK(q.sj_median == q.sj_min);
    CHECK(q.angle_deviation_median == doctest::Approx(std::atan(s) * 180 / kPi).epsilon(1e-14));
    CHECK(q.angle_deviation_p95 == q.angle_deviation_median);
    CHECK(q.sj_below_half == (s == 3.0 ? 1 : 0));  // 1/sqrt(10) = 0.316
    CHECK(q.area_ratio == doctest::Approx(1).epsilon(1e-15));
  }
}

TEST_CASE("measure_quads: a non-convex quad has SJ <= 0 (hand-computed corners)") {
  // Reflex corner at p2 = (0.5, 0.5): e1 = p3 - p2 = (-0.5, 1.5), e2 = p1 - p2 = (1.5, -0.5),
  // e1 x e2 = -2, |e1||e2| = 2.5, normal (p2 - p0) x (p3 - p1) = +2 z: SJ = -0.8. Angles: 90 at p0,
  // atan2(1, 3) at p1 and p3 (deviations 90 - 18.43 = atan 3), atan2(2, -1.5) at p2 (deviation atan
  // 0.75).
  const QuadMesh dart = planar({{{{0, 0, 0}, {2, 0, 0}, {0.5, 0.5, 0}, {0, 2, 0}}}});
  const QuadQuality q = measure(dart, triangulated(dart));
  CHECK(q.sj_min == doctest::Approx(-0.8).epsilon(1e-14));
  CHECK(q.sj_nonpositive == 1);
  CHECK(q.sj_below_half == 1);
  CHECK(q.degenerate == 0);
  // Area: split along p0-p2, 1/2 + 1/2; along p1-p3, 2 + 1 (the two overlap): the mean, 2, is twice
  // the input's (the quad split along p0-p2).
  CHECK(q.area_ratio == 2);
  // Deviations 0, 36.87, 71.57, 71.57: median the 2nd, p95 the 4th.
  CHECK(q.angle_deviation_median == doctest::Approx(std::atan(0.75) * 180 / kPi).epsilon(1e-14));
  CHECK(q.angle_deviation_p95 == doctest::Approx(std::atan(3.0) * 180 / kPi).epsilon(1e-14));
}

TEST_CASE("measure_quads: a fold adds area (and a quad flipped as a whole keeps SJ 1)") {
  // Input: the rectangle [0,2] x [0,1], area 2. Quads: [0,3] x [0,1] and [2,3] x [0,1] traversed
  // clockwise (folded back over the first): unsigned areas 3 + 1.
  const TriangleMesh input{{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  const QuadMesh folded =
      planar({rectangle(0, 3, 0, 1), {{{3, 0, 0}, {2, 0, 0}, {2, 1, 0}, {3, 1, 0}}}});
  const QuadQuality q = measure(folded, input);
  CHECK(q.area_ratio == 2);
  CHECK(q.sj_min == 1);  // each quad's normal is its own: the fold shows in the area only
  CHECK(q.smallest_half_area == 0.25);
  CHECK(q.area_p95_over_p5 == 3);
}

TEST_CASE("measure_quads: smallest_half_area and the area quantiles on quads of known areas") {
  const TriangleMesh input{{{0, 0, 0}, {8, 0, 0}, {8, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  // Areas 4, 1, 2, 1 (total 8): the two smallest cover 2.
  const QuadMesh row = planar(
      {rectangle(0, 4, 0, 1), rectangle(4, 5, 0, 1), rectangle(5, 7, 0, 1), rectangle(7, 8, 0, 1)});
  const QuadQuality q = measure(row, input);
  CHECK(q.smallest_half_area == 0.25);
  CHECK(q.area_p95_over_p5 == 4);  // p5: the 1st smallest (1), p95: the 4th (4)
  CHECK(q.area_ratio == 1);
  CHECK(q.valence == std::map<int, int>{{1, 16}});  // the quads share no vertex
  // Odd count: floor(3 / 2) = 1 quad of areas 1, 2, 3.
  const QuadMesh three =
      planar({rectangle(0, 3, 0, 1), rectangle(3, 4, 0, 1), rectangle(4, 6, 0, 1)});
  CHECK(measure(three, input).smallest_half_area == doctest::Approx(1.0 / 6).epsilon(1e-15));
  CHECK(measure(three, input).area_ratio == doctest::Approx(6.0 / 8).epsilon(1e-15));
}

TEST_CASE("measure_quads: degenerate quads count as SJ 0, a zero edge as a 0-degree corner") {
  const TriangleMesh input{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}};
  // A triangle written as a quad (p1 repeated): the corners at the zero edge deviate by 90.
  QuadMesh m{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 1, 2}}};
  QuadQuality q = measure(m, input);
  CHECK(q.degenerate == 1);
  CHECK(q.sj_min == 0);
  CHECK(q.sj_nonpositive == 1);
  CHECK(q.angle_deviation_p95 == 90);
  CHECK(q.valence == std::map<int, int>{{1, 2}, {2, 1}});  // vertex 1 counted once per corner
  // Parallel diagonals (all four corners on a line): zero normal.
  m = {{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {{0, 1, 2, 3}}};
  q = measure(m, input);
  CHECK(q.degenerate == 1);
  CHECK(q.sj_median == 0);
}

TEST_CASE("measure_quads: two-sided distance of an offset plane, and of partial overlaps") {
  // Input: the unit square at z = 0 (diagonal sqrt 2); quads: a 2 x 2 grid of it at z = 0.25.
  const TriangleMesh square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  const QuadMesh offset =
      planar({rectangle(0, 0.5, 0, 0.5, 0.25), rectangle(0.5, 1, 0, 0.5, 0.25),
              rectangle(0, 0.5, 0.5, 1, 0.25), rectangle(0.5, 1, 0.5, 1, 0.25)});
  QuadQuality q = measure(offset, square, true);
  CHECK(q.distance_max == doctest::Approx(0.25 / std::sqrt(2.0)).epsilon(1e-14));
  CHECK(q.distance_p99 == doctest::Approx(0.25 / std::sqrt(2.0)).epsilon(1e-14));

  // The quads cover half the input [0,2] x [0,1]: the input's vertex (2, 0) is at distance 1 from
  // them, over the input's diagonal sqrt 5 (the other side is all 0).
  const TriangleMesh wide{{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  const QuadMesh half = planar({rectangle(0, 1, 0, 1)});
  q = measure(half, wide, true);
  CHECK(q.distance_max == doctest::Approx(1 / std::sqrt(5.0)).epsilon(1e-14));
  // The other way round: the quad mesh's vertex (2, 0) is at distance 1 from the unit square,
  // over the unit square's diagonal sqrt 2.
  const QuadMesh wide_quads = planar({rectangle(0, 2, 0, 1)});
  q = measure(wide_quads, square, true);
  CHECK(q.distance_max == doctest::Approx(1 / std::sqrt(2.0)).epsilon(1e-14));
  // Samples on the quad: 4 vertices, 4 midpoints, 1 centre, at distances 0, 0, 1, 1 (vertices),
  // 0, 0.5, 1, 0 (midpoints), 0.5 (centre); input side all 0: the 99 % quantile of the 15 is the
  // largest (ceil(0.99 * 15) = 15).
  CHECK(q.distance_p99 == q.distance_max);
}

TEST_CASE("measure_quads: subsampling, empty sides, scale invariance, errors") {
  const QuadMesh cube = unit_cube();
  const TriangleMesh input = triangulated(cube);
  QuadQualityOptions o;
  o.max_samples = 5;
  QuadQuality q = measure_quads(cube.positions, cube.quads, input.positions, input.triangles, o);
  CHECK(q.distance_samples_quads == 5);
  CHECK(q.distance_samples_input == 5);
  CHECK(q.distance_max <= 1e-15);

  q = measure_quads(cube.positions, {}, input.positions, input.triangles);
  CHECK(q.quads == 0);
  CHECK(q.sj_median == 0);
  CHECK(q.valence == std::map<int, int>{{0, 8}});
  CHECK(q.distance_max == kInf);

  // Scale invariance down to the range ends (coordinates first scaled by a power of two).
  for (double scale : {1e-300, 1e300}) {
    QuadMesh sheared = planar({{{{0, 0, 0}, {1, 0, 0}, {1.5, 1, 0}, {0.5, 1, 0.25}}}});
    TriangleMesh in = triangulated(sheared);
    const QuadQuality reference = measure(sheared, in, true);
    for (Vec3d& p : sheared.positions) p = {p.x * scale, p.y * scale, p.z * scale};
    in.positions = sheared.positions;
    const QuadQuality s = measure(sheared, in, true);
    INFO("scale " << scale);
    CHECK(s.sj_min == doctest::Approx(reference.sj_min).epsilon(1e-12));
    CHECK(s.angle_deviation_p95 == doctest::Approx(reference.angle_deviation_p95).epsilon(1e-12));
    CHECK(s.area_ratio == doctest::Approx(reference.area_ratio).epsilon(1e-12));
    CHECK(s.distance_max == doctest::Approx(reference.distance_max).epsilon(1e-12));
    CHECK(std::isfinite(s.distance_max));
  }

  CHECK(kind_of([&] {
          measure_quads(cube.positions, {{0, 1, 2, 8}}, input.positions, input.triangles);
        }) == ErrorKind::IndexOutOfRange);
  CHECK(kind_of([&] {
          measure_quads(cube.positions, cube.quads, input.positions, {{0, 1, -1}});
        }) == ErrorKind::IndexOutOfRange);
  std::vector<Vec3d> bad = cube.positions;
  bad[3].z = kInf;
  CHECK(kind_of([&] { measure_quads(bad, cube.quads, input.positions, input.triangles); }) ==
        ErrorKind::NonFinite);
  o.max_samples = 0;
  CHECK(kind_of([&] {
          measure_quads(cube.positions, cube.quads, input.positions, input.triangles, o);
        }) == ErrorKind::InvalidArgument);
}

namespace {

// The unit square at z = 0 as two triangles whose first edge is axis-parallel, so that every
// quantity below is computed without rounding: (0,0), (1,0), (1,1) and (0,1), (0,0), (1,1).
const std::vector<Vec3d> kSquare = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<std::array<int, 3>> kSquareTriangles = {{0, 1, 2}, {3, 0, 2}};

// UV of each corner: its (x, y) mapped by f.
std::vector<std::array<Vec2d, 3>> uv_of(const std::vector<Vec3d>& p,
                                        const std::vector<std::array<int, 3>>& tris, auto&& f) {
  std::vector<std::array<Vec2d, 3>> uv;
  for (const auto& t : tris) uv.push_back({f(p[t[0]]), f(p[t[1]]), f(p[t[2]])});
  return uv;
}

}  // namespace

TEST_CASE("measure_igm: an isometry gives conformal 1, area 1, symmetric Dirichlet 4") {
  const IgmQuality q =
      measure_igm(kSquare, kSquareTriangles, uv_of(kSquare, kSquareTriangles, [](const Vec3d& p) {
                    return Vec2d{p.x, p.y};
                  }));
  CHECK(q.triangles == 2);
  CHECK(q.degenerate == 0);
  CHECK(q.conformal.median == 1);
  CHECK(q.conformal.max == 1);
  CHECK(q.area.p99 == 1);
  CHECK(q.area.max == 1);
  CHECK(q.symmetric_dirichlet == 4);

  // A tilted 3D square (rotated about x by 30 degrees, then about z by 40) with UVs its own plane
  // coordinates (the unrotated ones), translated in UV: an isometry up to rounding.
  const double a = 30 * kPi / 180, b = 40 * kPi / 180;
  std::vector<Vec3d> tilted;
  for (const Vec3d& p : kSquare) {
    const Vec3d r{p.x, p.y * std::cos(a), p.y * std::sin(a)};
    tilted.push_back(
        {r.x * std::cos(b) - r.y * std::sin(b), r.x * std::sin(b) + r.y * std::cos(b), r.z + 5});
  }
  const std::vector<std::array<int, 3>> tris = {{0, 1, 2}, {0, 2, 3}};
  const IgmQuality t = measure_igm(tilted, tris, uv_of(kSquare, tris, [](const Vec3d& p) {
                                     return Vec2d{p.x + 7, p.y - 3};
                                   }));
  CHECK(t.conformal.max == doctest::Approx(1).epsilon(1e-12));
  CHECK(t.area.max == doctest::Approx(1).epsilon(1e-12));
  CHECK(t.symmetric_dirichlet == doctest::Approx(4).epsilon(1e-12));
}

TEST_CASE("measure_igm: UV scaled by 2 in x gives conformal 2 exactly and symmetric Dirichlet 5") {
  // J = diag(2, 1) in the square's frame; the global scaling sqrt(sum A_3d / sum A_uv) = 1/sqrt 2
  // gives singular values sqrt 2 and 1/sqrt 2: 2 + 1/2 + 1/2 + 2 = 5. Areas all scale alike: 1.
  const IgmQuality q =
      measure_igm(kSquare, kSquareTriangles, uv_of(kSquare, kSquareTriangles, [](const Vec3d& p) {
                    return Vec2d{2 * p.x, p.y};
                  }));
  CHECK(q.conformal.median == 2);
  CHECK(q.conformal.p99 == 2);
  CHECK(q.conformal.max == 2);
  CHECK(q.area.max == 1);
  CHECK(q.symmetric_dirichlet == 5);
  // The same map with the 3D square scaled by 1e-200 and the UVs by 1e200 (a uniform scaling of
  // either changes nothing; the coordinates are first scaled by powers of two).
  std::vector<Vec3d> tiny = kSquare;
  for (Vec3d& p : tiny) p = {p.x * 1e-200, p.y * 1e-200, 0};
  const IgmQuality s =
      measure_igm(tiny, kSquareTriangles, uv_of(kSquare, kSquareTriangles, [](const Vec3d& p) {
                    return Vec2d{2e200 * p.x, 1e200 * p.y};
                  }));
  CHECK(s.conformal.max == doctest::Approx(2).epsilon(1e-14));
  CHECK(s.symmetric_dirichlet == doctest::Approx(5).epsilon(1e-14));
}

TEST_CASE("measure_igm: area distortion and weighted quantiles by hand, degenerate triangles") {
  // Both triangles have 3D area 1/2. UVs: the first its own coordinates (area 1/2), the second
  // stretched by 3 in x (area 3/2): r = (1/2 / 2) / (1/2 / 1) = 1/2 -> 2 and (3/2 / 2) / (1/2) =
  // 3/2.
  std::vector<Vec3d> p = kSquare;
  std::vector<std::array<int, 3>> tris = kSquareTriangles;
  std::vector<std::array<Vec2d, 3>> uv = {{{{0, 0}, {1, 0}, {1, 1}}}, {{{0, 1}, {0, 0}, {3, 1}}}};
  // Two degenerate triangles: collinear 3D corners, and a clockwise UV triangle.
  p.push_back({2, 2, 0});
  tris.push_back({0, 2, 4});
  uv.push_back({{{0, 0}, {1, 0}, {0, 1}}});
  tris.push_back({0, 1, 2});
  uv.push_back({{{0, 0}, {0, 1}, {1, 0}}});
  const IgmQuality q = measure_igm(p, tris, uv);
  CHECK(q.triangles == 4);
  CHECK(q.degenerate == 2);
  // Equal weights: the median is the smaller value (its weight reaches half), p90 the larger.
  CHECK(q.area.median == 1.5);
  CHECK(q.area.p90 == 2);
  CHECK(q.area.max == 2);
  CHECK(q.conformal.median == 1);
  CHECK(q.conformal.p90 == 3);
  // Scaled by 1/sqrt 2: singular values (1/sqrt 2, 1/sqrt 2) -> 1/2 + 1/2 + 2 + 2 = 5 and
  // (3/sqrt 2, 1/sqrt 2) -> 9/2 + 1/2 + 2/9 + 2 = 65/9; mean (5 + 65/9) / 2 = 55/9.
  CHECK(q.symmetric_dirichlet == doctest::Approx(55.0 / 9).epsilon(1e-14));

  // All degenerate: counted, metrics 0.
  const IgmQuality none = measure_igm(p, {{0, 2, 4}}, {{{{0, 0}, {1, 0}, {0, 1}}}});
  CHECK(none.degenerate == 1);
  CHECK(none.symmetric_dirichlet == 0);

  CHECK(kind_of([&] { measure_igm(p, tris, {}); }) == ErrorKind::InvalidArgument);
  CHECK(kind_of([&] { measure_igm(p, {{0, 1, 5}}, {uv[0]}); }) == ErrorKind::IndexOutOfRange);
  uv[1][2].x = std::nan("");
  CHECK(kind_of([&] { measure_igm(p, tris, uv); }) == ErrorKind::NonFinite);
}

TEST_CASE(
    "to_json and summary_line: key order, shortest numbers, null for inf, nan and unmeasured") {
  IgmQuality igm;
  igm.triangles = 2;
  igm.degenerate = 1;
  igm.conformal = {1, 1.5, 0.1, 2.5};
  igm.area = {1, 1, 1, kInf};
  igm.symmetric_dirichlet = 4.25;
  CHECK(to_json(igm) ==
        "{\"triangles\": 2, \"degenerate\": 1, \"conformal\": {\"median\": 1, \"p90\": 1.5, "
        "\"p99\": 0.1, "
        "\"max\": 2.5}, \"area\": {\"median\": 1, \"p90\": 1, \"p99\": 1, \"max\": null}, "
        "\"symmetric_dirichlet\": 4.25}");

  QuadQuality q;
  q.quads = 3;
  q.vertices = 8;
  q.valence = {{3, 8}, {10, 1}};
  q.sj_min = -0.25;
  q.sj_p5 = 0.5;
  q.sj_median = 0.75;
  q.sj_below_half = 1e-20;
  q.angle_deviation_median = std::nan("");
  q.area_ratio = 1.0 / 3;
  q.distance_max = 0.5;  // not measured: null
  CHECK(to_json(q) ==
        "{\"quads\": 3, \"vertices\": 8, \"degenerate\": 0, \"valence\": {\"3\": 8, \"10\": 1}, "
        "\"irregular_vertices\": 0, \"max_valence\": 0, \"sj_min\": -0.25, \"sj_p5\": 0.5, \"sj_median\": 0.75, \"sj_below_half\": 1e-20, "
        "\"sj_nonpositive\": 0, \"angle_deviation_median\": null, \"angle_deviation_p95\": 0, "
        "\"area_p95_over_p5\": 0, \"area_ratio\": 0.3333333333333333, \"smallest_half_area\": 0, "
        "\"distance_measured\": false, \"distance_max\": null, \"distance_p99\": null, "
        "\"distance_samples_quads\": 0, \"distance_samples_input\": 0}");
  q.distance_measured = true;
  CHECK(to_json(q).find("\"distance_max\": 0.5, \"distance_p99\": 0,") != std::string::npos);

  q.sj_below_half = 0.031;
  q.angle_deviation_median = 6.1;
  q.area_ratio = 0.998;
  q.smallest_half_area = 0.41;
  q.distance_max = 0.003;
  igm.conformal.p99 = 2.7;
  igm.area.p99 = 3.1;
  CHECK(
      summary_line(igm, q) ==
      "quads 3 (0 irregular vertices, valence <= 0): SJ median 0.75 p5 0.50 min -0.25, <0.5 3.1 %, "
      "<=0 0.0 %, angle dev median 6.1 deg, area/input 0.998, smallest half 41 %, distance max 0.3 %; "
      "IGM conformal p99 2.7, area p99 3.1");
}
