// Tests of the genus-0 cut with an independent checker recomputed from the raw arrays of the result.
#include <doctest/doctest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/topology/sphere_cut.h"
#include "generated_mesh.h"
#include "test_data.h"

using namespace igm;

namespace {

ValidMesh generated_sphere(std::int64_t faces, std::uint64_t seed) { return igm_test::generated_mesh(0, faces, seed); }

// Everything the cut promises, recomputed; returns "" or the first failure.
std::string verify(const ValidMesh& in, const SphereCut& c) {
  std::ostringstream err;
  const TriMesh& m = c.surface.mesh;
  const int nv = m.num_vertices(), nf = m.num_faces();
  if (!m.check_invariants().empty()) return "surface invariants: " + m.check_invariants();
  if (nv - m.num_edges() + nf != 2) return "surface is no longer a sphere";
  if (nv < in.mesh.num_vertices()) return "lost vertices";
  for (int v = 0; v < in.mesh.num_vertices(); ++v) {
    const Vec3d p = c.surface.position(v);
    if (p.x != in.positions[v].x || p.y != in.positions[v].y || p.z != in.positions[v].z) return "input vertex moved";
  }
  // the path: simple, along edges, cones where stated, no chords, cones pairwise non-adjacent
  const int k = static_cast<int>(c.path.size()) - 1;
  std::map<int, int> pos;
  for (int i = 0; i <= k; ++i)
    if (!pos.emplace(c.path[i], i).second) return "path repeats a vertex";
  for (int i = 0; i < k; ++i)
    if (m.find_halfedge(c.path[i], c.path[i + 1]) < 0) return "path step is not an edge";
  for (int j = 0; j < 4; ++j)
    if (c.path[c.cone_index[j]] != c.cones[j]) return "cone not at its path position";
  if (!(c.cone_index[0] == 0 && c.cone_index[0] < c.cone_index[1] && c.cone_index[1] < c.cone_index[2] &&
        c.cone_index[2] < c.cone_index[3] && c.cone_index[3] == k))
    return "cones not in path order";
  for (int h = 0; h < m.num_halfedges(); ++h) {
    const auto a = pos.find(m.origin(h)), b = pos.find(m.target(h));
    if (a != pos.end() && b != pos.end() && std::abs(a->second - b->second) != 1) return "chord left";
    for (int x : c.cones)
      for (int y : c.cones)
        if (x != y && m.origin(h) == x && m.target(h) == y) return "two cones adjacent";
  }
  // the disk: same faces, consistent copies, Euler characteristic 1, one boundary loop = `boundary`
  const int nd = static_cast<int>(c.disk_to_surface.size());
  if (nd != nv + k - 1 || static_cast<int>(c.disk_triangles.size()) != nf) return "disk sizes";
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < nf; ++f) {
    const auto s = m.face_vertices(f);
    for (int i = 0; i < 3; ++i) {
      const int d = c.disk_triangles[f][i];
      if (d < 0 || d >= nd || c.disk_to_surface[d] != s[i]) return "disk corner is not a copy of its surface corner";
      if (!directed.emplace(std::make_pair(d, c.disk_triangles[f][(i + 1) % 3]), f).second)
        return "disk edge used twice in one direction";
    }
  }
  std::set<std::pair<int, int>> undirected;
  std::map<int, int> boundary_next;
  for (const auto& [e, f] : directed) {
    undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
    if (!directed.count({e.second, e.first})) {
      if (boundary_next.count(e.first)) return "pinched boundary";
      boundary_next[e.first] = e.second;
    }
  }
  const long chi = long(nd) - long(undirected.size()) + nf;
  if (chi != 1) return "disk Euler characteristic " + std::to_string(chi);
  const int nb = static_cast<int>(c.boundary.size());
  if (nb != 2 * k || static_cast<int>(boundary_next.size()) != nb) return "boundary length";
  // The boundary half-edges run with the interior on their left, so the ccw cycle follows them.
  for (int i = 0; i < nb; ++i) {
    const auto it = boundary_next.find(c.boundary[i]);
    if (it == boundary_next.end() || it->second != c.boundary[(i + 1) % nb]) return "boundary cycle differs";
  }
  // six sides: A, B1, C1, D, C2, B2
  const int expect[6] = {c.cones[0], c.cones[1], c.cones[2], c.cones[3], c.cones[2], c.cones[1]};
  for (int s = 0; s < 6; ++s) {
    if (s > 0 && c.corners[s] <= c.corners[s - 1]) return "corners not increasing";
    if (c.disk_to_surface[c.boundary[c.corners[s]]] != expect[s]) return "corner " + std::to_string(s);
  }
  // every boundary vertex other than the corners is a path vertex, the two arcs mirror each other
  for (int i = 1; i < k; ++i)
    if (c.disk_to_surface[c.boundary[i]] != c.disk_to_surface[c.boundary[nb - i]]) return "arcs do not mirror";
  return err.str();
}

}  // namespace

TEST_CASE("sphere cut: shared genus-0 meshes give a disk with one 6-sided boundary") {
  IGM_REQUIRE_DATA(dir);
  for (const char* name : {"tetrahedron.off", "icosahedron.off", "cube.off", "sphere.off", "bull.off", "armadillo.off"}) {
    INFO(name);
    const ValidMesh in = load_mesh(dir / "meshes" / "clean" / name);
    const SphereCut c = cut_sphere(in.mesh, in.positions);
    CHECK(verify(in, c) == "");
    for (int x : c.cones) CHECK(x < in.mesh.num_vertices());  // cones are input vertices
  }
}

TEST_CASE("sphere cut: generated spheres, deterministic") {
  for (std::int64_t faces : {16, 100, 2000, 30000}) {
    INFO(faces);
    const ValidMesh in = generated_sphere(faces, std::uint64_t(faces));
    const SphereCut a = cut_sphere(in.mesh, in.positions);
    CHECK(verify(in, a) == "");
    const SphereCut b = cut_sphere(in.mesh, in.positions);
    CHECK(a.path == b.path);
    CHECK(a.cones == b.cones);
  }
}

TEST_CASE("sphere cut: the tetrahedron (all vertices cones) and the 3-vertex sphere are refined, not rejected") {
  PolygonSoup tet;
  tet.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.corners = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  tet.face_begin = {0, 3, 6, 9, 12};
  const ValidMesh t = validate(tet);
  const SphereCut ct = cut_sphere(t.mesh, t.positions);
  CHECK(verify(t, ct) == "");
  std::vector<int> cones(ct.cones.begin(), ct.cones.end());
  std::sort(cones.begin(), cones.end());
  CHECK(cones == std::vector<int>{0, 1, 2, 3});
  CHECK(ct.stats.cone_splits == 6);
  // two triangles on three vertices (coincident points, too: geometry plays no part)
  PolygonSoup pillow;
  pillow.positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  pillow.corners = {0, 1, 2, 1, 0, 2};
  pillow.face_begin = {0, 3, 6};
  const ValidMesh p = validate(pillow);
  REQUIRE(p.genus == 0);
  const SphereCut cp = cut_sphere(p.mesh, p.positions);
  CHECK(cp.stats.small_mesh_splits == 1);
  CHECK(verify(p, cp) == "");
}

TEST_CASE("sphere cut: user cones are kept in their order, bad lists are typed errors naming the entry") {
  const ValidMesh in = generated_sphere(500, 3);
  const int n = in.mesh.num_vertices();
  SphereCutOptions o;
  o.cones = {n - 1, 0, n / 2, 7};
  const SphereCut c = cut_sphere(in.mesh, in.positions, o);
  CHECK(verify(in, c) == "");
  CHECK(c.cones == std::array<int, 4>{n - 1, 0, n / 2, 7});
  struct Bad {
    std::vector<int> cones;
    const char* text;
  };
  for (const Bad& b : {Bad{{1, 2, 3}, "exactly 4"}, Bad{{1, 2, 3, 4, 5}, "exactly 4"}, Bad{{1, 2, 2, 4}, "entry 2 repeats"},
                       Bad{{1, -1, 3, 4}, "entry 1 is vertex -1"}, Bad{{1, 2, 3, n}, "entry 3 is vertex"}}) {
    o.cones = b.cones;
    try {
      cut_sphere(in.mesh, in.positions, o);
      FAIL("accepted a bad cone list");
    } catch (const Error& e) {
      CHECK(e.kind() == ErrorKind::InvalidArgument);
      CHECK(std::string(e.what()).find(b.text) != std::string::npos);
    }
  }
  GenerateOptions g;
  g.genus = 1;
  g.faces = 300;
  const ValidMesh torus = validate(generate_closed_mesh(g));
  CHECK_THROWS_AS(cut_sphere(torus.mesh, torus.positions), Error);
}
