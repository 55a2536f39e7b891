#include <doctest/doctest.h>

#include <random>
#include <set>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/trimesh.h"

using namespace igm;

namespace {
std::vector<std::array<int, 3>> triangles_of(const PolygonSoup& s) {
  std::vector<std::array<int, 3>> t;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto* c = &s.corners[s.face_begin[f]];
    t.push_back({int(c[0]), int(c[1]), int(c[2])});
  }
  return t;
}
int euler(const TriMesh& m) { return m.num_vertices() - m.num_edges() + m.num_faces(); }
const std::vector<std::array<int, 3>> kTetra = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
}  // namespace

TEST_CASE("tetrahedron builds with closed fans") {
  TriMesh m = TriMesh::from_triangles(4, kTetra);
  CHECK(m.check_invariants() == "");
  CHECK(m.num_edges() == 6);
  for (int v = 0; v < 4; ++v) CHECK(m.valence(v) == 3);
  CHECK(m.find_halfedge(0, 2) >= 0);
  CHECK(m.target(m.find_halfedge(0, 2)) == 2);
}

TEST_CASE("from_triangles rejects boundary, non-manifold and inconsistent orientation") {
  auto open = kTetra;
  open.pop_back();
  CHECK_THROWS_AS(TriMesh::from_triangles(4, open), Error);
  try {
    TriMesh::from_triangles(4, open);
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Boundary);
  }
  auto flipped = kTetra;
  std::swap(flipped[0][1], flipped[0][2]);
  try {
    TriMesh::from_triangles(4, flipped);
    FAIL("accepted an inconsistently oriented mesh");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::NonManifoldEdge);
  }
  try {
    TriMesh::from_triangles(3, kTetra);
    FAIL("accepted an out-of-range vertex");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::IndexOutOfRange);
  }
}

TEST_CASE("from_triangles with allow_boundary: boundary half-edges without twins, fans from them") {
  // The tetrahedron without face (0, 3, 2): a disk whose boundary 0 -> 2 -> 3 -> 0 runs along the
  // removed face's edges reversed; vertex 1, where the three faces meet, has a closed fan.
  auto open = kTetra;
  open.pop_back();
  const TriMesh m = TriMesh::from_triangles(4, open, /*allow_boundary=*/true);
  std::set<std::pair<int, int>> boundary;
  for (int h = 0; h < m.num_halfedges(); ++h) {
    if (m.twin(h) < 0) {
      boundary.insert({m.origin(h), m.target(h)});
      continue;
    }
    CHECK(m.twin(m.twin(h)) == h);
    CHECK(m.origin(m.twin(h)) == m.target(h));
  }
  CHECK(boundary == std::set<std::pair<int, int>>{{0, 2}, {2, 3}, {3, 0}});
  for (int v : {0, 2, 3}) {  // the first corner of its fan: the outgoing boundary half-edge
    CHECK(m.twin(m.vertex_halfedge(v)) < 0);
    CHECK(m.origin(m.vertex_halfedge(v)) == v);
  }
  CHECK(m.valence(1) == 3);  // closed fan
  // Without the option the same faces are refused; a closed mesh gives the same mesh either way.
  CHECK_THROWS_AS(TriMesh::from_triangles(4, open), Error);
  const TriMesh a = TriMesh::from_triangles(4, kTetra);
  const TriMesh b = TriMesh::from_triangles(4, kTetra, true);
  CHECK(a.twins() == b.twins());
  for (int v = 0; v < 4; ++v) CHECK(a.vertex_halfedge(v) == b.vertex_halfedge(v));
}

TEST_CASE("from_halfedges builds the mesh from_triangles builds from the same faces") {
  // A split mesh (its vertex half-edges and twins are the splits', not from_triangles') rebuilt
  // both ways: the same arrays, vertex half-edges included.
  TriMesh m = TriMesh::from_triangles(4, kTetra);
  std::mt19937 rng(3);
  for (int step = 0; step < 300; ++step) {
    if (rng() % 2) m.split_edge(int(rng() % m.num_halfedges()));
    else m.split_face(int(rng() % m.num_faces()));
  }
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < m.num_faces(); ++f) faces.push_back(m.face_vertices(f));
  const TriMesh a = TriMesh::from_triangles(m.num_vertices(), faces);
  const TriMesh b = TriMesh::from_halfedges(m.num_vertices(), m.origins(), m.twins());
  CHECK(b.check_invariants() == "");
  CHECK(b.origins() == a.origins());
  CHECK(b.twins() == a.twins());
  int differ = 0;  // the splits leave other vertex half-edges than the last one
  for (int v = 0; v < m.num_vertices(); ++v) {
    CHECK(b.vertex_halfedge(v) == a.vertex_halfedge(v));
    differ += m.vertex_halfedge(v) != a.vertex_halfedge(v);
  }
  CHECK(differ > 0);
}

TEST_CASE("from_halfedges rejects broken pairings and origins out of range, naming the half-edge") {
  const TriMesh m = TriMesh::from_triangles(4, kTetra);
  auto kind_of = [](int nv, std::vector<int> origin, std::vector<int> twin, std::int64_t* element = nullptr) {
    try {
      TriMesh::from_halfedges(nv, std::move(origin), std::move(twin));
    } catch (const Error& e) {
      if (element && !e.elements().empty()) *element = e.elements()[0];
      return e.kind();
    }
    FAIL("accepted broken half-edge arrays");
    return ErrorKind::Io;
  };
  CHECK(kind_of(3, m.origins(), m.twins()) == ErrorKind::IndexOutOfRange);
  {  // two half-edges of different edges swapped as twins: no involution, or wrong ends
    std::vector<int> twin = m.twins();
    const int h = 0, g = m.twin(h), k = m.twin(1);
    twin[h] = k;
    std::int64_t at = -1;
    CHECK(kind_of(4, m.origins(), twin, &at) == ErrorKind::Internal);
    CHECK(at == h);
    twin[k] = h, twin[1] = g, twin[g] = 1;  // an involution again, between the wrong vertices
    at = -1;
    CHECK(kind_of(4, m.origins(), twin, &at) == ErrorKind::Internal);
    CHECK(at == 0);
  }
  {
    std::vector<int> twin = m.twins();
    twin[5] = 5;  // its own twin
    CHECK(kind_of(4, m.origins(), twin) == ErrorKind::Internal);
    twin[5] = -1;
    CHECK(kind_of(4, m.origins(), twin) == ErrorKind::Internal);
  }
  std::vector<int> short_twin = m.twins();
  short_twin.pop_back();
  CHECK(kind_of(4, m.origins(), short_twin) == ErrorKind::Internal);
}

TEST_CASE("random edge and face splits keep every invariant and the Euler characteristic") {
  TriMesh m = TriMesh::from_triangles(4, kTetra);
  std::mt19937 rng(7);
  for (int step = 0; step < 2000; ++step) {
    if (rng() % 2) {
      int h = int(rng() % m.num_halfedges());
      int a = m.origin(h), b = m.target(h);
      int v = m.split_edge(h);
      CHECK(m.find_halfedge(a, v) >= 0);
      CHECK(m.find_halfedge(v, b) >= 0);
      CHECK(m.find_halfedge(a, b) == -1);
      CHECK(m.valence(v) == 4);
    } else {
      int v = m.split_face(int(rng() % m.num_faces()));
      CHECK(m.valence(v) == 3);
    }
    if (step % 97 == 0) REQUIRE(m.check_invariants() == "");
  }
  REQUIRE(m.check_invariants() == "");
  CHECK(euler(m) == 2);
}

TEST_CASE("generated meshes are closed manifolds of the requested genus") {
  for (int g : {0, 1, 2, 3, 5, 12, 40}) {
    for (std::int64_t faces : {16, 1000, 20000}) {
      GenerateOptions o;
      o.genus = g;
      o.faces = faces;
      o.seed = std::uint64_t(g * 131 + faces);
      PolygonSoup s = generate_closed_mesh(o);
      TriMesh m = TriMesh::from_triangles(int(s.positions.size()), triangles_of(s));
      INFO("genus " << g << " faces " << faces);
      REQUIRE(m.check_invariants() == "");
      CHECK(euler(m) == 2 - 2 * g);
      if (faces >= 1000) CHECK(m.num_faces() <= 3 * faces);
    }
  }
}

TEST_CASE("generator is deterministic for a seed and varies with it") {
  GenerateOptions o;
  o.genus = 3;
  o.faces = 3000;
  auto a = generate_closed_mesh(o), b = generate_closed_mesh(o);
  CHECK(a.corners == b.corners);
  o.seed = 2;
  auto c = generate_closed_mesh(o);
  CHECK(a.corners != c.corners);
  o.genus = -1;
  CHECK_THROWS_AS(generate_closed_mesh(o), Error);
}
