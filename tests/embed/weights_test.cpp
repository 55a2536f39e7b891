#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "igm/core/error.h"
#include "igm/embed/weights.h"

using namespace igm;

namespace {

// A flat fan: vertex 0 at the origin with 6 neighbours on the unit circle (equilateral triangles).
struct Fan {
  std::vector<Vec3d> p;
  std::vector<std::array<int, 3>> t;
};
Fan hexagon_fan() {
  Fan f;
  f.p.push_back({0, 0, 0});
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 6; ++k) f.p.push_back({std::cos(k * pi / 3), std::sin(k * pi / 3), 0});
  for (int k = 0; k < 6; ++k) f.t.push_back({0, 1 + k, 1 + (k + 1) % 6});
  return f;
}

// The weight of the edge (a, b) from the half-edge weights (checked equal on both halves).
int weight_of(const Fan& f, const std::vector<int>& w, int a, int b) {
  int found = -1;
  for (std::size_t t = 0; t < f.t.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int u = f.t[t][i], v = f.t[t][(i + 1) % 3];
      if ((u == a && v == b) || (u == b && v == a)) {
        if (found >= 0) CHECK(found == w[3 * t + i]);
        found = w[3 * t + i];
      }
    }
  return found;
}

}  // namespace

TEST_CASE("weights: uniform is 1 everywhere, all symmetric, positive, in [1, 2^16]") {
  const Fan f = hexagon_fan();
  for (WeightKind k : {WeightKind::Uniform, WeightKind::Cotan, WeightKind::MeanValue}) {
    CAPTURE(to_string(k));
    const std::vector<int> w = edge_weights(f.p, f.t, k);
    REQUIRE(w.size() == 3 * f.t.size());
    for (int x : w) CHECK((x >= 1 && x <= 65536));
    if (k == WeightKind::Uniform)
      for (int x : w) CHECK(x == 1);
  }
}

TEST_CASE("weights: on the regular hexagon fan by hand") {
  const Fan f = hexagon_fan();
  // Cotan: spokes cot 60 + cot 60 = 2/sqrt 3, rim edges (one triangle) cot 60 = 1/sqrt 3; the median
  // of the 12 edges is the spokes' value m, so spokes get m / (m / 256) = 256, rims 128.
  const std::vector<int> c = edge_weights(f.p, f.t, WeightKind::Cotan);
  CHECK(weight_of(f, c, 0, 1) == 256);
  CHECK(weight_of(f, c, 1, 2) == 128);
  // Mean value: spoke from the centre tan(30) + tan(30) over length 1, from the rim tan(30) +
  // tan(30) over 1: 4 tan 30 in all; a rim edge gets tan(30) / 1 from each end: 2 tan 30. The
  // median (of 6 at 4t and 6 at 2t, the upper middle) is 4t: spokes 256, rims 128.
  const std::vector<int> m = edge_weights(f.p, f.t, WeightKind::MeanValue);
  CHECK(weight_of(f, m, 0, 3) == 256);
  CHECK(weight_of(f, m, 3, 4) == 128);
}

TEST_CASE("weights: obtuse corners clamp cotan weights to the low end, never below 1") {
  // A flat kite whose spoke (0, 2) faces two angles of 150 degrees: cot sum < 0.
  std::vector<Vec3d> p = {{0, 0, 0}, {1, 0.1, 0}, {2, 0, 0}, {1, -0.1, 0}};
  std::vector<std::array<int, 3>> t = {{0, 2, 1}, {0, 3, 2}};
  const std::vector<int> c = edge_weights(p, t, WeightKind::Cotan);
  CHECK(c[0] == 1);  // edge (0, 2)
  for (int x : c) CHECK(x >= 1);
}

TEST_CASE("weights: degenerate and non-finite triangles still get positive finite weights") {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vec3d> p = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {inf, 0, 0}, {0, 1, 0}};
  std::vector<std::array<int, 3>> t = {{0, 1, 2}, {0, 2, 3}, {2, 3, 4}, {0, 2, 5}};
  for (WeightKind k : {WeightKind::Cotan, WeightKind::MeanValue}) {
    const std::vector<int> w = edge_weights(p, t, k);
    for (int x : w) CHECK((x >= 1 && x <= 65536));
  }
  CHECK_THROWS_AS(edge_weights(p, {{0, 1, 9}}, WeightKind::Cotan), Error);
}
