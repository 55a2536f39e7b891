#include <doctest/doctest.h>

#include <random>

#include "igm/arrange/planar_walk.h"
#include "igm/core/error.h"

using namespace igm;

TEST_CASE("locate_point finds vertices, edges and faces exactly") {
  PlanarTriangulation m;
  m.positions = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  const PlanarAdjacency adj = PlanarAdjacency::build(4, m.triangles);
  for (int from = 0; from < 4; ++from) {
    auto l = locate_point(m.positions, m.triangles, adj, from, {1, 1});
    CHECK(l.kind == PlanarLocation::Kind::Edge);
    l = locate_point(m.positions, m.triangles, adj, from, {2, 2});
    CHECK(l.kind == PlanarLocation::Kind::Vertex);
    CHECK(m.triangles[l.triangle][l.index] == 2);
    l = locate_point(m.positions, m.triangles, adj, from, {Rational(1, 3), Rational(1, 2)});
    CHECK(l.kind == PlanarLocation::Kind::Face);
    CHECK(l.triangle == 1);
    l = locate_point(m.positions, m.triangles, adj, from, {2, 1});
    CHECK(l.kind == PlanarLocation::Kind::Edge);
    CHECK_THROWS_AS(locate_point(m.positions, m.triangles, adj, from, {3, 1}), Error);
  }
}
