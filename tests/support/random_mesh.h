#pragma once
// Random meshes with hostile geometry, shared by the randomized property tests (tests/random/)
// and the pipeline fuzz target (fuzz/pipeline_fuzz.cpp).
//
// A mesh is generate_mesh(genus, faces, seed, boundaries) (a tetrahedron for a closed genus 0
// below 16 faces), refined by random edge and face splits, given near-degenerate or extreme
// geometry (which must not matter for topology), and finally put in random vertex order, face
// order and corner rotation. The combinatorics (oriented, connected, genus g, `boundaries`
// boundary loops) are never changed by the geometry, so validate() must accept every closed such
// mesh and the pipeline must certify it; validate_surfaces() must find one surface of genus g
// with `boundaries` loops in every one.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/soup.h"
#include "igm/mesh/trimesh.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"

namespace igm_test {

/// How vertex positions are replaced after refinement (all finite: topology must not care).
enum class Geometry {
  Plain,       // the generator's positions (refinement vertices at edge midpoints / centroids)
  Tiny,        // all scaled by 1e-300: squared edge lengths underflow to 0
  Huge,        // all scaled by 1e300: squared edge lengths overflow to inf
  Extreme,     // every coordinate +-1e308 at random: differences overflow to inf
  Mixed,       // each vertex scaled by 1e-300, 1 or 1e300 at random
  Collinear,   // every vertex on one line, at few distinct parameters (collinear and coincident)
  Coincident,  // every vertex at the same point
  Collapse,    // about half the vertices moved onto another vertex (coincident points)
  Count
};

inline const char* to_string(Geometry g) {
  static const char* names[] = {"plain",     "tiny",       "huge",     "extreme", "mixed",
                                "collinear", "coincident", "collapse", "?"};
  return names[static_cast<int>(g)];
}

struct RandomMeshSpec {
  int genus = 1;                 // 0..12 in the tests and the fuzz target
  std::int64_t faces = 200;      // generator target (min 16); genus 0 below 16: a tetrahedron (4)
  std::uint64_t seed = 1;        // everything below is drawn from this seed
  double jitter = 0.25;          // generator's in-plane jitter, [0, 0.5)
  int edge_splits = 0;           // random edge splits after generation
  int face_splits = 0;           // random face splits after generation
  Geometry geometry = Geometry::Plain;
  bool permute = true;           // random vertex order, face order and corner rotation
  int boundaries = 0;            // boundary loops (generate.h: B <= the generator's capacity)
};

inline std::string describe(const RandomMeshSpec& s) {
  return "genus " + std::to_string(s.genus) + ", faces " + std::to_string(s.faces) + ", seed " +
         std::to_string(s.seed) + ", jitter " + std::to_string(s.jitter) + ", edge splits " +
         std::to_string(s.edge_splits) + ", face splits " + std::to_string(s.face_splits) +
         ", geometry " + to_string(s.geometry) + (s.permute ? ", permuted" : "") +
         (s.boundaries > 0 ? ", boundaries " + std::to_string(s.boundaries) : "");
}

/// The triangles of a mesh as a soup over `positions`.
inline igm::PolygonSoup to_soup(const igm::TriMesh& m, const std::vector<igm::Vec3d>& positions) {
  igm::PolygonSoup soup;
  soup.positions = positions;
  for (int f = 0; f < m.num_faces(); ++f) {
    const auto t = m.face_vertices(f);
    soup.add_face(t.begin(), t.end());
  }
  return soup;
}

/// A random relabelling of the soup: vertex ids permuted, faces reordered, each face's corners
/// rotated (orientation kept). Same surface, same genus.
inline igm::PolygonSoup permute_soup(const igm::PolygonSoup& in, std::mt19937_64& rng, bool vertices = true,
                                     bool faces = true, bool rotate = true) {
  const std::size_t nv = in.positions.size(), nf = in.num_faces();
  std::vector<std::int64_t> vmap(nv);  // old id -> new id
  std::iota(vmap.begin(), vmap.end(), 0);
  if (vertices) std::shuffle(vmap.begin(), vmap.end(), rng);
  std::vector<std::size_t> order(nf);  // new face position -> old face
  std::iota(order.begin(), order.end(), 0);
  if (faces) std::shuffle(order.begin(), order.end(), rng);
  igm::PolygonSoup out;
  out.positions.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) out.positions[static_cast<std::size_t>(vmap[v])] = in.positions[v];
  std::vector<std::int64_t> face;
  for (std::size_t f : order) {  // nf faces, each of face_size(f) corners
    const std::size_t k = in.face_size(f);
    const std::size_t r = rotate ? static_cast<std::size_t>(rng() % k) : 0;
    face.clear();
    for (std::size_t i = 0; i < k; ++i) face.push_back(vmap[static_cast<std::size_t>(in.corners[in.face_begin[f] + (i + r) % k])]);
    out.add_face(face.begin(), face.end());
  }
  return out;
}

/// Replaces the positions as `geometry` says (see Geometry). Bound: one pass over the vertices.
inline void apply_geometry(std::vector<igm::Vec3d>& p, Geometry geometry, std::mt19937_64& rng) {
  const std::size_t n = p.size();
  if (n == 0) return;
  auto scale = [](igm::Vec3d& q, double s) { q = {q.x * s, q.y * s, q.z * s}; };
  switch (geometry) {
    case Geometry::Plain:
    case Geometry::Count:
      break;
    case Geometry::Tiny:
      for (auto& q : p) scale(q, 1e-300);
      break;
    case Geometry::Huge:
      for (auto& q : p) scale(q, 1e300);
      break;
    case Geometry::Extreme:
      for (auto& q : p) {
        auto c = [&] { return (rng() & 1) ? 1e308 : -1e308; };
        q = {c(), c(), c()};
      }
      break;
    case Geometry::Mixed:
      for (auto& q : p) scale(q, std::array<double, 3>{1e-300, 1.0, 1e300}[rng() % 3]);
      break;
    case Geometry::Collinear:
      for (auto& q : p) {
        const double t = static_cast<double>(rng() % 5);  // few parameters: many coincident points
        q = {t, 2 * t, -3 * t};
      }
      break;
    case Geometry::Coincident:
      for (auto& q : p) q = {1.0, 2.0, 3.0};
      break;
    case Geometry::Collapse:
      for (auto& q : p)
        if (rng() & 1) q = p[rng() % n];
      break;
  }
}

/// Random edge and face splits of an oriented triangle surface with boundary (TriMesh needs a
/// closed one): an edge split replaces its one or two triangles by two each, a face split one
/// triangle by three around a new vertex. Bound: edge_splits + face_splits iterations.
inline void split_open_mesh(std::vector<std::array<int, 3>>& tris, std::vector<igm::Vec3d>& pos,
                            int edge_splits, int face_splits, std::mt19937_64& rng) {
  std::map<std::pair<int, int>, int> half;  // (origin, target) -> 3 t + i
  const auto set = [&](int t, int i) {
    half[{tris[static_cast<std::size_t>(t)][static_cast<std::size_t>(i)],
          tris[static_cast<std::size_t>(t)][static_cast<std::size_t>((i + 1) % 3)]}] = 3 * t + i;
  };
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int i = 0; i < 3; ++i) set(t, i);
  // Triangle (a, b, c) of half-edge h = a -> b becomes (a, m, c), and (m, b, c) is added.
  const auto cut = [&](int h, int m) {
    const int t = h / 3, i = h % 3;
    auto& tri = tris[static_cast<std::size_t>(t)];
    const int b = tri[static_cast<std::size_t>((i + 1) % 3)],
              c = tri[static_cast<std::size_t>((i + 2) % 3)];
    half.erase({tri[static_cast<std::size_t>(i)], b});
    tri[static_cast<std::size_t>((i + 1) % 3)] = m;
    set(t, i);
    set(t, (i + 1) % 3);
    tris.push_back({m, b, c});
    for (int k = 0; k < 3; ++k) set(static_cast<int>(tris.size()) - 1, k);
  };
  auto mid = [](const igm::Vec3d& a, const igm::Vec3d& b) {
    return igm::Vec3d{0.5 * a.x + 0.5 * b.x, 0.5 * a.y + 0.5 * b.y, 0.5 * a.z + 0.5 * b.z};
  };
  int e = edge_splits, f = face_splits;
  while (e + f > 0) {
    const int nt = static_cast<int>(tris.size());
    if (f == 0 || (e > 0 && rng() % static_cast<unsigned>(e + f) < static_cast<unsigned>(e))) {
      const int h = static_cast<int>(rng() % static_cast<unsigned>(3 * nt));
      const int a = tris[static_cast<std::size_t>(h / 3)][static_cast<std::size_t>(h % 3)];
      const int b = tris[static_cast<std::size_t>(h / 3)][static_cast<std::size_t>((h + 1) % 3)];
      const int m = static_cast<int>(pos.size());
      pos.push_back(mid(pos[static_cast<std::size_t>(a)], pos[static_cast<std::size_t>(b)]));
      const auto twin = half.find({b, a});
      const int h2 = twin == half.end() ? -1 : twin->second;
      cut(h, m);
      if (h2 >= 0) cut(h2, m);
      --e;
    } else {
      const int t = static_cast<int>(rng() % static_cast<unsigned>(nt));
      const auto v = tris[static_cast<std::size_t>(t)];
      const int m = static_cast<int>(pos.size());
      pos.push_back(
          mid(mid(pos[static_cast<std::size_t>(v[0])], pos[static_cast<std::size_t>(v[1])]),
              pos[static_cast<std::size_t>(v[2])]));
      half.erase({v[1], v[2]});
      half.erase({v[2], v[0]});
      tris[static_cast<std::size_t>(t)] = {v[0], v[1], m};
      tris.push_back({v[1], v[2], m});
      tris.push_back({v[2], v[0], m});
      for (int s : {t, nt, nt + 1})
        for (int k = 0; k < 3; ++k) set(s, k);
      --f;
    }
  }
}

/// The random mesh of `spec` (see the top of this file). Deterministic in `spec`.
inline igm::PolygonSoup random_mesh(const RandomMeshSpec& spec) {
  std::mt19937_64 rng(spec.seed);
  igm::PolygonSoup soup;
  if (spec.genus == 0 && spec.faces < 16 && spec.boundaries == 0) {
    soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (auto t : {std::array<std::int64_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) soup.add_face(t.begin(), t.end());
  } else {
    igm::GenerateOptions g;
    g.genus = spec.genus;
    g.faces = spec.faces;
    g.seed = rng();
    g.jitter = spec.jitter;
    g.shuffle = false;  // permuted below, after the refinements
    g.boundaries = spec.boundaries;
    soup = igm::generate_mesh(g);
  }
  if (spec.boundaries > 0 && (spec.edge_splits > 0 || spec.face_splits > 0)) {
    igm::SurfaceComponent c = igm::validate_surfaces(soup).components.at(0);
    split_open_mesh(c.triangles, c.positions, spec.edge_splits, spec.face_splits, rng);
    soup = igm::PolygonSoup{};
    soup.positions = std::move(c.positions);
    for (const auto& t : c.triangles) soup.add_face({t[0], t[1], t[2]});
  } else if (spec.edge_splits > 0 || spec.face_splits > 0) {
    igm::ValidMesh v = igm::validate(soup);
    igm::TriMesh& m = v.mesh;
    std::vector<igm::Vec3d>& pos = v.positions;
    auto mid = [](const igm::Vec3d& a, const igm::Vec3d& b) {
      return igm::Vec3d{0.5 * a.x + 0.5 * b.x, 0.5 * a.y + 0.5 * b.y, 0.5 * a.z + 0.5 * b.z};
    };
    int e = spec.edge_splits, f = spec.face_splits;
    while (e + f > 0) {  // edge_splits + face_splits iterations
      if (f == 0 || (e > 0 && rng() % (e + f) < static_cast<unsigned>(e))) {
        const int h = static_cast<int>(rng() % static_cast<unsigned>(m.num_halfedges()));
        const igm::Vec3d a = pos[m.origin(h)], b = pos[m.target(h)];
        m.split_edge(h);
        pos.push_back(mid(a, b));
        --e;
      } else {
        const int face = static_cast<int>(rng() % static_cast<unsigned>(m.num_faces()));
        const auto t = m.face_vertices(face);
        m.split_face(face);
        pos.push_back(mid(mid(pos[t[0]], pos[t[1]]), pos[t[2]]));
        --f;
      }
    }
    soup = to_soup(m, pos);
  }
  apply_geometry(soup.positions, spec.geometry, rng);
  if (spec.permute) soup = permute_soup(soup, rng);
  return soup;
}

/// A closed 12-face box (the unit cube, two triangles a side, outward).
inline igm::PolygonSoup box_soup() {
  igm::PolygonSoup soup;
  for (int i = 0; i < 8; ++i) soup.positions.push_back({double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1)});
  const std::array<std::array<std::int64_t, 4>, 6> sides{{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                                          {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  for (const auto& q : sides) {
    soup.add_face({q[0], q[1], q[2]});
    soup.add_face({q[0], q[2], q[3]});
  }
  return soup;
}

/// A mesh of several components (tests/random, fuzz/pipeline_fuzz.cpp): each a 4-face tetrahedron
/// or a 12-face box (3/8 each), or a random_mesh of genus floor((max_genus + 1) u^3) (closed, or
/// open with 1..3 loops a quarter of the time), scaled
/// by 10^u, u uniform in [0, orders] (sizes up to `orders` orders of magnitude apart) and moved
/// apart; faces of the generated ones log-uniform from what the generator needs up to max_faces.
struct RandomSurfaces {
  igm::PolygonSoup soup;
  std::vector<std::array<int, 2>> topology;  // per component, in soup order: (genus, boundary loops)
  std::string description;                   // one line per component, for failure messages
};

inline RandomSurfaces random_surfaces(std::uint64_t seed, int components, int max_genus, std::int64_t max_faces,
                                      double orders = 4) {
  std::mt19937_64 rng(seed);
  RandomSurfaces out;
  double x = 0;  // components side by side along x
  for (int c = 0; c < components; ++c) {  // bound: components
    const unsigned kind = static_cast<unsigned>(rng() % 8 / 3);  // 0: tetrahedron, 1: box (3/8 each), 2: generated
    igm::PolygonSoup part;
    RandomMeshSpec s;
    s.seed = rng();
    if (kind == 0) {
      s.genus = 0;
      s.faces = 4;
      part = random_mesh(s);
      out.description += "tetrahedron";
    } else if (kind == 1) {
      s.genus = 0;
      part = permute_soup(box_soup(), rng);
      out.description += "box";
    } else {
      // Low genera more often: genus = floor((max_genus + 1) u^3).
      const double u = std::uniform_real_distribution<double>(0, 1)(rng);
      s.genus = std::min(max_genus, static_cast<int>((max_genus + 1) * u * u * u));
      s.boundaries = rng() % 4 == 0 ? 1 + static_cast<int>(rng() % 3) : 0;
      const double least = s.boundaries > 0 ? 200.0 + 250.0 * s.genus + 40.0 * s.boundaries : 16.0 + 60.0 * s.genus;
      const double most = std::max(least, static_cast<double>(max_faces));
      s.faces = static_cast<std::int64_t>(least * std::pow(most / least, std::uniform_real_distribution<double>(0, 1)(rng)));
      s.jitter = std::uniform_real_distribution<double>(0, 0.45)(rng);
      s.edge_splits = static_cast<int>(rng() % 6);
      s.face_splits = static_cast<int>(rng() % 6);
      part = random_mesh(s);
      out.description += describe(s);
    }
    // Its size: 10^u of a unit, u in [0, orders]; placed beyond the components before it.
    const double size = std::pow(10.0, std::uniform_real_distribution<double>(0, orders)(rng));
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const igm::Vec3d& p : part.positions) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
    const double extent = std::max({hi - lo, 1.0, 1e-300});
    const double k = size / extent;
    const auto base = static_cast<std::int64_t>(out.soup.positions.size());
    for (const igm::Vec3d& p : part.positions) out.soup.positions.push_back({x + k * (p.x - lo), k * p.y, k * p.z});
    for (std::size_t f = 0; f < part.num_faces(); ++f) {
      std::vector<std::int64_t> face;
      for (std::size_t i = part.face_begin[f]; i < part.face_begin[f + 1]; ++i) face.push_back(part.corners[i] + base);
      out.soup.add_face(face.begin(), face.end());
    }
    x += 1.5 * size;
    out.topology.push_back({s.genus, s.boundaries});
    out.description += ", size " + std::to_string(size) + "\n";
  }
  return out;
}

/// random_mesh for a closed spec (boundaries = 0), as the closed-mesh suites call it.
inline igm::PolygonSoup random_closed_mesh(const RandomMeshSpec& spec) {
  if (spec.boundaries != 0)
    throw igm::Error(igm::ErrorKind::InvalidArgument, "random_closed_mesh: boundaries != 0");
  return random_mesh(spec);
}

}  // namespace igm_test
