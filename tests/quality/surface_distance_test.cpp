#include "igm/quality/surface_distance.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "error_kind.h"
#include "generated_mesh.h"
#include "igm/core/error.h"

using namespace igm;
using igm_test::kind_of;

namespace {

double distance(const Vec3d& a, const Vec3d& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

// Within 1e-15 of the hand-computed point (coordinates of size ~1: a few ulps).
void check_point(const Vec3d& got, const Vec3d& want) {
  INFO("got (" << got.x << ", " << got.y << ", " << got.z << "), want (" << want.x << ", " << want.y
               << ", " << want.z << ")");
  CHECK(distance(got, want) <= 1e-15);
}

struct Soup {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 3>> triangles;
};

// n random triangles in the unit cube, some of them slivers or degenerate.
Soup random_soup(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Soup s;
  for (int t = 0; t < n; ++t) {
    const Vec3d c{u(rng), u(rng), u(rng)};
    const double size = 0.02 + 0.2 * u(rng);
    const int first = static_cast<int>(s.positions.size());
    for (int i = 0; i < 3; ++i)
      s.positions.push_back(
          {c.x + size * (u(rng) - 0.5), c.y + size * (u(rng) - 0.5), c.z + size * (u(rng) - 0.5)});
    if (t % 17 == 0)
      s.positions[first + 2] = s.positions[first];  // a degenerate triangle (segment)
    if (t % 23 == 0) {                              // collinear corners
      const Vec3d& a = s.positions[first];
      const Vec3d& b = s.positions[first + 1];
      s.positions[first + 2] = {2 * b.x - a.x, 2 * b.y - a.y, 2 * b.z - a.z};
    }
    s.triangles.push_back({first, first + 1, first + 2});
  }
  return s;
}

double brute_force(const Soup& s, const Vec3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : s.triangles)
    best = std::min(best,
                    distance(p, closest_point_on_triangle(p, s.positions[t[0]], s.positions[t[1]],
                                                          s.positions[t[2]])));
  return best;
}

}  // namespace

TEST_CASE("closest_point_on_triangle: face, edge and vertex regions by hand") {
  const Vec3d a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  // Face region: the orthogonal projection.
  check_point(closest_point_on_triangle({0.25, 0.25, 2}, a, b, c), {0.25, 0.25, 0});
  check_point(closest_point_on_triangle({0.1, 0.7, -3}, a, b, c), {0.1, 0.7, 0});
  // Vertex regions: a (both edges from a point away), b, c.
  check_point(closest_point_on_triangle({-1, -1, 1}, a, b, c), a);
  check_point(closest_point_on_triangle({2, -0.5, 0}, a, b, c), b);
  check_point(closest_point_on_triangle({0, 3, -1}, a, b, c), c);
  // Edge regions: ab, the hypotenuse bc, ca.
  check_point(closest_point_on_triangle({0.5, -1, 0}, a, b, c), {0.5, 0, 0});
  check_point(closest_point_on_triangle({1, 1, 0.5}, a, b, c), {0.5, 0.5, 0});
  check_point(closest_point_on_triangle({-2, 0.5, 7}, a, b, c), {0, 0.5, 0});
  // Beyond the hypotenuse but nearer to b than to its interior: the vertex, reached through an
  // edge.
  check_point(closest_point_on_triangle({3, -0.5, 0}, a, b, c), b);
  // On the triangle itself: the point.
  check_point(closest_point_on_triangle({0.5, 0.5, 0}, a, b, c), {0.5, 0.5, 0});
}

TEST_CASE("closest_point_on_triangle: degenerate triangles are the union of their edges") {
  const Vec3d a{0, 0, 0}, b{1, 0, 0}, c{2, 0, 0};  // collinear: the segment a-c
  check_point(closest_point_on_triangle({3, 1, 0}, a, b, c), c);
  check_point(closest_point_on_triangle({1.5, 1, 0}, a, b, c), {1.5, 0, 0});
  check_point(closest_point_on_triangle({-1, 0, 2}, a, b, c), a);
  check_point(closest_point_on_triangle({0.5, 0, 1}, a, a, b), {0.5, 0, 0});  // a repeated corner
  check_point(closest_point_on_triangle({4, 5, 6}, b, b, b), b);              // a point
}

TEST_CASE("closest_point_on_triangle: no sample of the triangle is nearer, on random cases") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int round = 0; round < 200; ++round) {
    const Vec3d a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)};
    const Vec3d p{2 * u(rng), 2 * u(rng), 2 * u(rng)};
    const Vec3d q = closest_point_on_triangle(p, a, b, c);
    const double d = distance(p, q);
    // q lies in the triangle: its barycentric coordinates (least squares) are >= 0 and sum to 1,
    // and it is no farther than the best of a 50 x 50 barycentric grid of the triangle.
    double best_grid = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 50; ++i)
      for (int j = 0; i + j <= 50; ++j) {
        const double v = i / 50.0, w = j / 50.0, s = 1 - v - w;
        const Vec3d y{s * a.x + v * b.x + w * c.x, s * a.y + v * b.y + w * c.y,
                      s * a.z + v * b.z + w * c.z};
        best_grid = std::min(best_grid, distance(p, y));
      }
    CHECK(d <= best_grid + 1e-12);
    const Vec3d ab{b.x - a.x, b.y - a.y, b.z - a.z}, ac{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3d aq{q.x - a.x, q.y - a.y, q.z - a.z};
    auto dot = [](const Vec3d& x, const Vec3d& y) { return x.x * y.x + x.y * y.y + x.z * y.z; };
    const double d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac);
    const double den = d00 * d11 - d01 * d01;
    const double v = (d11 * dot(aq, ab) - d01 * dot(aq, ac)) / den;
    const double w = (d00 * dot(aq, ac) - d01 * dot(aq, ab)) / den;
    CHECK(v >= -1e-9);
    CHECK(w >= -1e-9);
    CHECK(v + w <= 1 + 1e-9);
    // A point of the triangle's plane.
    const Vec3d n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
    CHECK(std::fabs(dot(aq, n)) <= 1e-14 * std::sqrt(dot(n, n)));
  }
}

TEST_CASE("TriangleBvh: nearest agrees with brute force on random soups and a generated mesh") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.5, 1.5);
  std::vector<Soup> soups = {random_soup(1, 1), random_soup(5, 2), random_soup(700, 3)};
  const ValidMesh g = igm_test::generated_mesh(2, 3000, 5);
  Soup mesh;
  mesh.positions = g.positions;
  for (int f = 0; f < g.mesh.num_faces(); ++f) mesh.triangles.push_back(g.mesh.face_vertices(f));
  soups.push_back(mesh);
  for (const Soup& s : soups) {
    const TriangleBvh bvh(s.positions, s.triangles);
    CHECK(bvh.size() == s.triangles.size());
    std::vector<Vec3d> queries;
    for (int i = 0; i < 150; ++i) {
      // Mesh queries near its vertices (near the surface), soup queries anywhere around it.
      const Vec3d& v = s.positions[rng() % s.positions.size()];
      queries.push_back(&s == &soups.back()
                            ? Vec3d{v.x + 0.3 * u(rng), v.y + 0.3 * u(rng), v.z + 0.1 * u(rng)}
                            : Vec3d{u(rng), u(rng), u(rng)});
    }
    const std::vector<double> all = bvh.distances(queries);
    REQUIRE(all.size() == queries.size());
    int hint = -1;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const Vec3d& p = queries[i];
      const double want = brute_force(s, p);
      const SurfaceNearest r = bvh.nearest(p);
      const SurfaceNearest hinted = bvh.nearest(p, hint);
      hint = hinted.triangle;
      INFO("query " << i << " of a set of " << s.triangles.size() << " triangles");
      CHECK(r.distance == doctest::Approx(want).epsilon(1e-12));
      CHECK(hinted.distance == doctest::Approx(want).epsilon(1e-12));
      CHECK(all[i] == doctest::Approx(want).epsilon(1e-12));
      // The answer is consistent: the point is on the triangle named, at the distance given.
      REQUIRE(r.triangle >= 0);
      const auto& t = s.triangles[r.triangle];
      check_point(
          closest_point_on_triangle(p, s.positions[t[0]], s.positions[t[1]], s.positions[t[2]]),
          r.point);
      CHECK(distance(p, r.point) == r.distance);
    }
  }
}

TEST_CASE("TriangleBvh: equal centroids, empty set, errors") {
  // 300 copies of one triangle: every Morton code equal, ranges split at the middle.
  std::vector<Vec3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::vector<std::array<int, 3>> copies(300, {0, 1, 2});
  const TriangleBvh same(p, copies);
  CHECK(same.nearest({0.25, 0.25, 3}).distance == 3);
  CHECK(same.distances({{2, 0, 0}, {0, 0, -1}}) == std::vector<double>{1, 1});

  const TriangleBvh empty(p, {});
  CHECK(empty.size() == 0);
  CHECK(empty.nearest({0, 0, 0}).distance == std::numeric_limits<double>::infinity());
  CHECK(empty.nearest({0, 0, 0}).triangle == -1);
  CHECK(std::isinf(empty.distances({{1, 2, 3}})[0]));

  CHECK(kind_of([&] { TriangleBvh(p, {{0, 1, 3}}); }) == ErrorKind::IndexOutOfRange);
  p[1].y = std::nan("");
  CHECK(kind_of([&] { TriangleBvh(p, {{0, 1, 2}}); }) == ErrorKind::NonFinite);
  p[1].y = 0;
  CHECK(kind_of([&] { same.nearest({0, 0, 0}, 300); }) == ErrorKind::InvalidArgument);
  CHECK(kind_of([&] { same.distances({{0, std::nan(""), 0}}); }) == ErrorKind::NonFinite);
}
