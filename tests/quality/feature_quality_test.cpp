// measure_features (quality/quality.h): coverage of feature curves by quad edges.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include "error_kind.h"
#include "igm/core/error.h"
#include "igm/quality/quality.h"

namespace {

using igm::Vec3d;

// The 8 corners of [-1, 1]^3 and its 12 edges (the features of a cube).
struct CubeFeatures {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 2>> edges;
};
CubeFeatures cube_features() {
  CubeFeatures c;
  for (int i = 0; i < 8; ++i) c.positions.push_back({i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? 1.0 : -1.0});
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) c.edges.push_back({i, i | bit});
  return c;
}

// The faces of [-s, s]^3 as n x n grids of quads (faces listed in `sides`: axis * 2 + (side > 0)).
struct Quads {
  std::vector<Vec3d> positions;
  std::vector<std::array<int, 4>> quads;
};
Quads cube_quads(int n, double s, const std::vector<int>& sides = {0, 1, 2, 3, 4, 5}) {
  Quads q;
  for (int f : sides) {
    const int axis = f / 2;
    const double side = f % 2 ? s : -s;
    const int base = static_cast<int>(q.positions.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        double c[3];
        c[axis] = side;
        c[(axis + 1) % 3] = -s + 2 * s * i / n;
        c[(axis + 2) % 3] = -s + 2 * s * j / n;
        q.positions.push_back({c[0], c[1], c[2]});
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = base + i * (n + 1) + j;
        q.quads.push_back({a, a + n + 1, a + n + 2, a + 1});
      }
  }
  return q;
}

}  // namespace

TEST_CASE("measure_features: a cube's quads cover its creases, a grown cube's by a known distance") {
  const CubeFeatures f = cube_features();
  const double diagonal = 2 * std::sqrt(3.0);
  {
    const Quads q = cube_quads(3, 1);
    const igm::FeatureQuality r = igm::measure_features(f.positions, f.edges, q.positions, q.quads);
    CHECK(r.edges == 12);
    CHECK(r.length == doctest::Approx(24));
    CHECK(r.covered_fraction == 1.0);
    CHECK(r.distance_max <= 1e-15);  // rounding of the samples' positions only
    CHECK(r.distance_p99 <= 1e-15);
    CHECK(r.samples >= static_cast<std::size_t>(24 / (0.0005 * diagonal)));
  }
  // Grown by 0.002: each crease sqrt(2) 0.002 from the grown one (0.08 % < 0.2 %): covered.
  {
    const Quads q = cube_quads(2, 1.002);
    const igm::FeatureQuality r = igm::measure_features(f.positions, f.edges, q.positions, q.quads);
    CHECK(r.covered_fraction == 1.0);
    CHECK(r.distance_max == doctest::Approx(std::sqrt(2.0) * 0.002 / diagonal));
  }
  // Grown by 0.01 (0.41 %): none covered.
  {
    const Quads q = cube_quads(5, 1.01);
    const igm::FeatureQuality r = igm::measure_features(f.positions, f.edges, q.positions, q.quads);
    CHECK(r.covered_fraction == 0.0);
    CHECK(r.distance_max == doctest::Approx(std::sqrt(2.0) * 0.01 / diagonal));
    CHECK(r.distance_p99 == doctest::Approx(std::sqrt(2.0) * 0.01 / diagonal));
  }
}

TEST_CASE("measure_features: only the top face's quads cover a third of the creases (and the tolerance)") {
  const CubeFeatures f = cube_features();
  const double diagonal = 2 * std::sqrt(3.0);
  const Quads q = cube_quads(4, 1, {5});  // z = 1
  const igm::FeatureQuality r = igm::measure_features(f.positions, f.edges, q.positions, q.quads);
  // The top 4 creases (length 8) and 0.002 x diagonal of each vertical one, out of 24.
  const double expected = (8 + 4 * 0.002 * diagonal) / 24;
  CHECK(std::fabs(r.covered_fraction - expected) <= 4 * 0.0005 * diagonal / 24);
  CHECK(r.distance_max == doctest::Approx(2 / diagonal).epsilon(1e-3));  // the bottom creases
  CHECK(r.distance_p99 == doctest::Approx(2 / diagonal).epsilon(1e-3));
  // A tolerance of 60 % of the diagonal covers everything.
  igm::FeatureQualityOptions o;
  o.tolerance = 0.6;
  CHECK(igm::measure_features(f.positions, f.edges, q.positions, q.quads, o).covered_fraction == 1.0);
  // Same bits on a second call, and scale invariance by a power of two.
  const igm::FeatureQuality again = igm::measure_features(f.positions, f.edges, q.positions, q.quads);
  CHECK(again.covered_fraction == r.covered_fraction);
  CHECK(again.distance_p99 == r.distance_p99);
  CubeFeatures big = f;
  Quads bigq = q;
  for (Vec3d& p : big.positions) p = {p.x * 1024, p.y * 1024, p.z * 1024};
  for (Vec3d& p : bigq.positions) p = {p.x * 1024, p.y * 1024, p.z * 1024};
  const igm::FeatureQuality scaled = igm::measure_features(big.positions, big.edges, bigq.positions, bigq.quads);
  CHECK(scaled.covered_fraction == r.covered_fraction);
  CHECK(scaled.distance_max == r.distance_max);
  CHECK(scaled.length == 1024 * r.length);
}

TEST_CASE("measure_features: no features, no quads, bad input") {
  const CubeFeatures f = cube_features();
  const Quads q = cube_quads(1, 1);
  const igm::FeatureQuality none = igm::measure_features(f.positions, {}, q.positions, q.quads);
  CHECK(none.edges == 0);
  CHECK(std::isnan(none.covered_fraction));
  CHECK(igm::to_json(none).find("\"covered_fraction\": null") != std::string::npos);
  CHECK(igm::summary_line(none) == "no features");
  const igm::FeatureQuality empty = igm::measure_features(f.positions, f.edges, {}, {});
  CHECK(empty.covered_fraction == 0.0);
  CHECK(std::isinf(empty.distance_max));
  CHECK(igm_test::kind_of([&] { igm::measure_features(f.positions, {{0, 8}}, q.positions, q.quads); }) ==
        igm::ErrorKind::IndexOutOfRange);
  std::vector<Vec3d> bad = f.positions;
  bad[3].x = std::numeric_limits<double>::quiet_NaN();
  CHECK(igm_test::kind_of([&] { igm::measure_features(bad, f.edges, q.positions, q.quads); }) == igm::ErrorKind::NonFinite);
  igm::FeatureQualityOptions o;
  o.spacing = 0;
  CHECK(igm_test::kind_of([&] { igm::measure_features(f.positions, f.edges, q.positions, q.quads, o); }) ==
        igm::ErrorKind::InvalidArgument);
  // max_samples bounds the samples.
  o = {};
  o.max_samples = 100;
  CHECK(igm::measure_features(f.positions, f.edges, q.positions, q.quads, o).samples <= 100 + 12);
}
