#include "igm/mesh/validate.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

#include "igm/core/union_find.h"
#include "igm/io/read_mesh.h"
#include "validate_internal.h"

namespace igm {

namespace {

constexpr std::size_t kMaxElements = 100;  // ids kept per problem
constexpr std::size_t kMaxNamed = 5;       // ids named in a message


// Union-find that also keeps each element's parity relative to its root: used to 2-colour the
// faces into "keep" and "flip" so that every manifold edge is traversed once in each direction.
struct ParityDsu {
  std::vector<int> parent, size;
  std::vector<char> parity;  // relative to parent
  explicit ParityDsu(std::size_t n) : parent(n), size(n, 1), parity(n, 0) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  std::pair<int, int> find(int x) {  // (root, parity of x relative to root)
    int p = 0, r = x;
    while (parent[r] != r) {  // bounded by the height, O(log n) with union by size
      p ^= parity[r];
      r = parent[r];
    }
    // path compression: point every visited node at the root with its full parity
    int q = x, pq = p;
    while (parent[q] != q) {  // same path again
      const int next = parent[q];
      const int pn = pq ^ parity[q];
      parent[q] = r;
      parity[q] = static_cast<char>(pq);
      q = next;
      pq = pn;
    }
    return {r, p};
  }
  // Requires parity(a) ^ parity(b) == d; returns false on a contradiction.
  bool unite(int a, int b, int d) {
    auto [ra, pa] = find(a);
    auto [rb, pb] = find(b);
    if (ra == rb) return (pa ^ pb) == d;
    if (size[ra] < size[rb]) std::swap(ra, rb);
    parent[rb] = ra;
    parity[rb] = static_cast<char>(pa ^ pb ^ d);
    size[ra] += size[rb];
    return true;
  }
};

// Collects one kind of problem: the exact count, the first ids, a few named examples.
struct Collector {
  std::int64_t count = 0;
  std::vector<std::int64_t> elements;
  std::vector<std::string> examples;
  void add(std::int64_t id, const std::string& example = {}) {
    ++count;
    if (elements.size() < kMaxElements) elements.push_back(id);
    if (!example.empty() && examples.size() < kMaxNamed) examples.push_back(example);
  }
  void add_without_id(const std::string& example) {
    ++count;
    if (examples.size() < kMaxNamed) examples.push_back(example);
  }
  void add_ids(const std::vector<std::int64_t>& ids, const std::string& example) {
    ++count;
    for (std::int64_t id : ids)
      if (elements.size() < kMaxElements) elements.push_back(id);
    if (!example.empty() && examples.size() < kMaxNamed) examples.push_back(example);
  }
  // Whether a new example would still be named (callers skip building the text otherwise).
  bool named() const { return examples.size() < kMaxNamed; }
  std::string list() const {
    std::string s;
    for (std::size_t i = 0; i < examples.size(); ++i) {
      if (i) s += "; ";
      s += examples[i];
    }
    if (count > static_cast<std::int64_t>(examples.size())) s += "; ...";
    return s;
  }
};

std::string ids_text(const std::vector<std::int64_t>& ids, std::size_t max = kMaxNamed) {
  std::string s;
  for (std::size_t i = 0; i < ids.size() && i < max; ++i) {
    if (i) s += ", ";
    s += std::to_string(ids[i]);
  }
  if (ids.size() > max) s += ", ...";
  return s;
}

std::string plural(std::int64_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string join_text(const std::vector<std::string>& parts) {
  std::string s;
  for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? "; " : "") + parts[i];
  return s;
}

bool is_finite(const Vec3d& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
  return static_cast<std::uint64_t>(lo) << 32 | hi;
}

int hnext(int h) { return h % 3 == 2 ? h - 2 : h + 1; }

// A half-edge keyed by its undirected edge: hd = 2 h + (origin > target).
struct HalfKey {
  std::uint64_t key;
  std::uint32_t hd;
};

// Stable LSD radix sort by key, 11-bit digits; digits that are zero in every key are skipped
// (edge keys use about 2 log2(V) bits). Cost O(n) per pass, at most 6 passes.
void radix_sort(std::vector<HalfKey>& v) {
  std::uint64_t all = 0;
  for (const HalfKey& x : v) all |= x.key;
  std::vector<HalfKey> tmp(v.size());
  constexpr int kBits = 11;
  constexpr std::size_t kBuckets = std::size_t{1} << kBits;
  std::vector<std::size_t> start(kBuckets + 1);
  for (int shift = 0; shift < 64; shift += kBits) {
    if (((all >> shift) & (kBuckets - 1)) == 0) continue;
    std::fill(start.begin(), start.end(), 0);
    for (const HalfKey& x : v) ++start[((x.key >> shift) & (kBuckets - 1)) + 1];
    for (std::size_t b = 0; b < kBuckets; ++b) start[b + 1] += start[b];
    for (const HalfKey& x : v) tmp[start[(x.key >> shift) & (kBuckets - 1)]++] = x;
    v.swap(tmp);
  }
}

}  // namespace

namespace validate_internal {

Analysis analyze(const PolygonSoup& soup, const ValidateOptions& opt, Mode mode) {
  const bool surfaces = mode != Mode::Closed, split = mode == Mode::SplitSurfaces;
  Analysis a;
  MeshReport& r = a.report;
  r.warnings = soup.warnings;  // the reader's come first
  const std::size_t nv = soup.positions.size();
  const std::size_t nf = soup.face_begin.empty() ? 0 : soup.num_faces();
  r.vertices = static_cast<std::int64_t>(nv);
  r.faces = static_cast<std::int64_t>(nf);
  auto emit = [&](ErrorKind kind, const Collector& c, const std::string& message) {
    if (c.count > 0) r.problems.push_back({kind, message, c.elements, c.count});
  };

  if (nv == 0) {
    r.problems.push_back({ErrorKind::Empty, "the mesh has no vertices", {}, 1});
    return a;
  }
  if (nf == 0) {
    r.problems.push_back({ErrorKind::NoFaces,
                          "the mesh has " + plural(static_cast<std::int64_t>(nv), "vertex", "vertices") +
                              " but no faces (a point cloud)",
                          {},
                          1});
    r.unreferenced_vertices = static_cast<std::int64_t>(nv);
    return a;
  }

  // --- 3, 4: sizes and soup structure ---
  bool malformed = soup.face_begin.front() != 0 || soup.face_begin.back() != soup.corners.size();
  for (std::size_t f = 0; f < nf && !malformed; ++f) malformed = soup.face_begin[f] > soup.face_begin[f + 1];
  if (malformed) {
    r.problems.push_back(
        {ErrorKind::InvalidArgument, "malformed polygon soup (face_begin does not index corners)", {}, 1});
    return a;
  }
  std::uint64_t num_tris = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::size_t k = soup.face_size(f);
    if (k >= 3) num_tris += k - 2;
    if (k > 3) ++r.polygons;
  }
  if (nv > static_cast<std::size_t>(INT_MAX) || num_tris > static_cast<std::uint64_t>(INT_MAX / 3)) {
    r.problems.push_back({ErrorKind::TooLarge,
                          "the mesh has " + std::to_string(nv) + " vertices and " + std::to_string(num_tris) +
                              " triangles: more than 32-bit half-edge ids hold",
                          {},
                          1});
    return a;
  }
  r.triangles = static_cast<std::int64_t>(num_tris);

  // --- 4, 5, 6: per face, O(k log k) for k corners ---
  Collector small, out_of_range, repeated;
  std::vector<char> referenced(nv, 0);
  std::vector<std::int64_t> sorted;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::int64_t* c = soup.corners.data() + soup.face_begin[f];
    const std::size_t k = soup.face_size(f);
    const auto fid = static_cast<std::int64_t>(f);
    if (k < 3)
      small.add(
          fid, !small.named() ? std::string() : "face " + std::to_string(f) + " has " + std::to_string(k) + " corners");
    bool bad = false;
    for (std::size_t i = 0; i < k; ++i)
      if (c[i] < 0 || c[i] >= static_cast<std::int64_t>(nv)) {
        if (!bad)
          out_of_range.add(fid, !out_of_range.named() ? std::string()
                                                      : "face " + std::to_string(f) + " uses vertex " +
                                                            std::to_string(c[i]) + (c[i] < 0 ? " (negative)" : ""));
        bad = true;
      } else {
        referenced[c[i]] = 1;
      }
    sorted.assign(c, c + k);
    std::sort(sorted.begin(), sorted.end());
    const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
    if (dup != sorted.end())
      repeated.add(fid, !repeated.named()
                            ? std::string()
                            : "face " + std::to_string(f) + " uses vertex " + std::to_string(*dup) + " twice");
  }
  emit(ErrorKind::InvalidArgument, small,
       plural(small.count, "face has", "faces have") + " fewer than 3 corners: " + small.list());
  emit(ErrorKind::IndexOutOfRange, out_of_range,
       plural(out_of_range.count, "face uses", "faces use") + " a vertex id outside 0.." + std::to_string(nv - 1) +
           ": " + out_of_range.list());
  emit(ErrorKind::RepeatedVertex, repeated,
       plural(repeated.count, "face uses", "faces use") + " a vertex twice: " + repeated.list());

  // --- 7: coordinates of the vertices that stay ---
  a.keep_vertex.assign(nv, 0);
  Collector non_finite;
  for (std::size_t v = 0; v < nv; ++v) {
    a.keep_vertex[v] = referenced[v] || !opt.drop_unreferenced;
    if (!referenced[v]) ++r.unreferenced_vertices;
    if (a.keep_vertex[v] && !is_finite(soup.positions[v]))
      non_finite.add(static_cast<std::int64_t>(v), !non_finite.named() ? std::string() : "vertex " + std::to_string(v));
  }
  emit(ErrorKind::NonFinite, non_finite,
       plural(non_finite.count, "vertex has", "vertices have") + " a NaN or infinite coordinate: " + non_finite.list());
  if (small.count + out_of_range.count + repeated.count > 0) return a;  // no well-defined complex
  r.topology_checked = true;

  // --- triangulation (fan; apex chosen to avoid diagonals that are existing edges) ---
  std::vector<std::uint64_t> input_edges;
  if (r.polygons > 0) {
    input_edges.reserve(soup.corners.size());
    for (std::size_t f = 0; f < nf; ++f) {
      const std::int64_t* c = soup.corners.data() + soup.face_begin[f];
      const std::size_t k = soup.face_size(f);
      for (std::size_t i = 0; i < k; ++i) input_edges.push_back(edge_key(int(c[i]), int(c[(i + 1) % k])));
    }
    std::sort(input_edges.begin(), input_edges.end());
  }
  const std::size_t T = num_tris;
  a.tris.reserve(T);
  a.tri_face.reserve(T);
  std::vector<char> diagonal(3 * T, 0);  // half-edge made by the triangulation
  for (std::size_t f = 0; f < nf; ++f) {
    const std::int64_t* c = soup.corners.data() + soup.face_begin[f];
    const std::size_t k = soup.face_size(f);
    std::size_t apex = 0;
    if (k > 3 && k <= 64) {
      for (std::size_t j = 0; j < k; ++j) {  // at most 64 * 64 lookups
        bool clash = false;
        for (std::size_t i = 2; i + 1 < k && !clash; ++i)
          clash = std::binary_search(input_edges.begin(), input_edges.end(), edge_key(int(c[j]), int(c[(j + i) % k])));
        if (!clash) {
          apex = j;
          break;
        }
      }
    }
    for (std::size_t i = 1; i + 1 < k; ++i) {
      const std::size_t t = a.tris.size();
      a.tris.push_back({int(c[apex]), int(c[(apex + i) % k]), int(c[(apex + i + 1) % k])});
      a.tri_face.push_back(static_cast<int>(f));
      diagonal[3 * t] = i != 1;
      diagonal[3 * t + 2] = i + 2 != k;
    }
  }
  if (r.polygons > 0)
    r.warnings.push_back("triangulated " + plural(r.polygons, "polygon", "polygons") +
                         " with more than 3 corners (fans): " + std::to_string(r.faces) + " faces became " +
                         std::to_string(T) + " triangles");

  // --- edges: sort half-edges by undirected key (the key carries the endpoints, so the
  // grouping below reads no triangle: it streams through the sorted array) ---
  const auto origin = [&](int h) { return a.tris[h / 3][h % 3]; };
  std::vector<HalfKey> keys(3 * T);
  for (std::size_t h = 0; h < 3 * T; ++h) {
    const int o = origin(int(h)), t = origin(hnext(int(h)));
    keys[h] = {edge_key(o, t), static_cast<std::uint32_t>(2 * h + (o > t ? 1 : 0))};
  }
  radix_sort(keys);

  UnionFind corners(3 * T);  // corner h = (triangle h/3, vertex origin(h)); joined across manifold edges
  ParityDsu orient(T);       // flip(t1) xor flip(t2) == "same direction" on every manifold edge
  std::vector<std::pair<int, int>> witness;  // (h1, h2) of each orientation contradiction
  std::vector<int> boundary;                 // boundary half-edges
  Collector nm_edges, inconsistent;
  std::vector<std::string> cut_edges;  // split: every cut edge, named
  if (surfaces) a.twin.assign(3 * T, -1);
  // Pairs h1 and h2 as the two half-edges of a manifold edge (same: of the same direction).
  const auto join = [&](int h1, int h2, bool same) {
    corners.unite(h1, same ? h2 : hnext(h2));
    corners.unite(hnext(h1), same ? hnext(h2) : h2);
    if (!orient.unite(h1 / 3, h2 / 3, same ? 1 : 0)) witness.push_back({h1, h2});
    if (surfaces) {
      a.twin[h1] = h2;
      a.twin[h2] = h1;
    }
  };
  for (std::size_t i = 0; i < keys.size();) {  // each round consumes one group of equal keys
    std::size_t j = i;
    while (j < keys.size() && keys[j].key == keys[i].key) ++j;
    ++r.edges;
    const int h1 = static_cast<int>(keys[i].hd >> 1);
    const int lo = static_cast<int>(keys[i].key >> 32), hi = static_cast<int>(keys[i].key & 0xffffffffu);
    auto edge = [&] { return "edge (" + std::to_string(lo) + ", " + std::to_string(hi) + ")"; };
    if (j - i == 1) {
      boundary.push_back(h1);
    } else if (j - i == 2) {
      const int h2 = static_cast<int>(keys[i + 1].hd >> 1);
      const bool same = (keys[i].hd & 1) == (keys[i + 1].hd & 1);
      join(h1, h2, same);
      if (same) {
        const int f1 = a.tri_face[h1 / 3], f2 = a.tri_face[h2 / 3];
        inconsistent.add_ids({f1, f2}, !inconsistent.named()
                                           ? std::string()
                                           : edge() + " in faces " + std::to_string(f1) + " and " + std::to_string(f2));
      }
    } else if (split) {
      // Cut: the k-th half-edge lo -> hi pairs with the k-th hi -> lo (both in input order,
      // the stable sort keeps it); the others become boundary edges.
      std::vector<int> up, down;
      std::vector<std::int64_t> faces;
      for (std::size_t k = i; k < j; ++k) {
        const int h = static_cast<int>(keys[k].hd >> 1);
        (keys[k].hd & 1 ? down : up).push_back(h);
        faces.push_back(a.tri_face[h / 3]);
      }
      const int group = static_cast<int>(cut_edges.size());
      const std::size_t pairs = std::min(up.size(), down.size());
      for (std::size_t k = 0; k < pairs; ++k) {
        join(up[k], down[k], false);
        a.pieces.push_back({group, up[k], down[k]});
      }
      for (const auto* rest : {&up, &down})
        for (std::size_t k = pairs; k < rest->size(); ++k) {
          boundary.push_back((*rest)[k]);
          a.pieces.push_back({group, (*rest)[k], -1});
        }
      const auto single = static_cast<std::int64_t>(j - i - 2 * pairs);
      cut_edges.push_back(edge() + " of faces " + ids_text(faces, faces.size()) + " into " +
                          plural(static_cast<std::int64_t>(pairs), "pair", "pairs") + " and " +
                          plural(single, "boundary edge", "boundary edges"));
    } else {
      std::vector<std::int64_t> faces;
      int diag_face = -1;
      for (std::size_t k = i; k < j; ++k) {
        const int h = static_cast<int>(keys[k].hd >> 1);
        faces.push_back(a.tri_face[h / 3]);
        if (diagonal[h]) diag_face = a.tri_face[h / 3];
      }
      std::string ex;
      if (nm_edges.named()) {
        ex = edge() + " has " + std::to_string(j - i) + " faces (" + ids_text(faces, 8) + ")";
        if (diag_face >= 0) ex += ", made by the fan triangulation of polygon " + std::to_string(diag_face);
      }
      nm_edges.add_ids(faces, ex);
    }
    i = j;
  }
  r.non_manifold_edges = nm_edges.count;
  r.boundary_edges = static_cast<std::int64_t>(boundary.size());
  r.inconsistently_oriented_edges = inconsistent.count;
  emit(ErrorKind::NonManifoldEdge, nm_edges,
       plural(nm_edges.count, "edge has", "edges have") + " more than two faces: " + nm_edges.list());
  if (!cut_edges.empty()) {
    r.non_manifold_edges = static_cast<std::int64_t>(cut_edges.size());
    r.warnings.push_back(
        "cut " + plural(r.non_manifold_edges, "edge", "edges") +
        " with more than two faces (opposite faces paired in input order, the others"
        " left as boundary edges): " +
        join_text(cut_edges));
  }

  // --- 9: fans per vertex ---
  std::vector<int> fans(nv, 0);
  for (std::size_t h = 0; h < 3 * T; ++h)
    if (corners.find(int(h)) == int(h)) ++fans[origin(int(h))];
  Collector nm_vertices;
  std::vector<std::string> cut_vertices;  // split: every cut vertex, named
  std::int64_t copies = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (fans[v] > 1) {
      const std::string name =
          "vertex " + std::to_string(v) + " (" + std::to_string(fans[v]) + " fans)";
      nm_vertices.add(static_cast<std::int64_t>(v), !nm_vertices.named() ? std::string() : name);
      if (split) cut_vertices.push_back(name);
      copies += fans[v];
    }
  r.non_manifold_vertices = nm_vertices.count;
  if (split) {
    if (!cut_vertices.empty())
      r.warnings.push_back(
          "cut " + plural(nm_vertices.count, "non-manifold vertex", "non-manifold vertices") +
          " into one copy per fan (" + std::to_string(copies) +
          " vertices in all): " + join_text(cut_vertices));
  } else {
    emit(ErrorKind::NonManifoldVertex, nm_vertices,
         plural(nm_vertices.count, "vertex has", "vertices have") +
             " faces forming more than one fan: " + nm_vertices.list());
  }

  // --- 10: orientation (the parity unions were made with the edges above) ---
  {
    std::vector<char> bad_root(T, 0);
    Collector non_orientable;
    for (auto [h1, h2] : witness) {
      const int root = orient.find(h1 / 3).first;
      if (bad_root[root]) continue;
      bad_root[root] = 1;
      const int f1 = a.tri_face[h1 / 3], f2 = a.tri_face[h2 / 3];
      const int u = origin(h1), w = origin(hnext(h1));
      non_orientable.add_ids({f1, f2}, "the component of face " + std::to_string(f1) +
                                           " (orientation contradiction at edge (" + std::to_string(std::min(u, w)) +
                                           ", " + std::to_string(std::max(u, w)) + ") between faces " +
                                           std::to_string(f1) + " and " + std::to_string(f2) + ")");
    }
    r.orientable = non_orientable.count == 0;
    emit(ErrorKind::NonOrientable, non_orientable,
         plural(non_orientable.count, "component is", "components are") + " not orientable: " + non_orientable.list());

    // Flip the minority orientation of each orientable component (ties: keep the lowest triangle's).
    std::vector<std::int64_t> count0(T, 0), count1(T, 0);
    std::vector<int> first_parity(T, -1);
    for (std::size_t t = 0; t < T; ++t) {
      auto [root, p] = orient.find(int(t));
      (p ? count1 : count0)[root]++;
      if (first_parity[root] < 0) first_parity[root] = p;
    }
    a.flip.assign(T, 0);
    for (std::size_t t = 0; t < T; ++t) {
      auto [root, p] = orient.find(int(t));
      if (bad_root[root]) continue;
      const int keep = count0[root] > count1[root] ? 0 : count1[root] > count0[root] ? 1 : first_parity[root];
      a.flip[t] = p != keep;
      r.flipped_faces += a.flip[t];
    }
  }
  if (inconsistent.count > 0) {
    if (opt.repair_orientation) {
      r.warnings.push_back("re-oriented " + plural(r.flipped_faces, "triangle", "triangles") + ": " +
                           plural(inconsistent.count, "edge joined", "edges joined") +
                           " two faces of the same direction (" + inconsistent.list() + ")");
    } else {
      emit(ErrorKind::NonManifoldEdge, inconsistent,
           plural(inconsistent.count, "edge joins", "edges join") +
               " two faces of the same direction (repair_orientation is off): " + inconsistent.list());
    }
  }

  // --- 11: boundary loops: connected components of the graph of boundary edges (loops that
  // touch at a vertex count as one, as the shared meshes' README counts them) ---
  {
    UnionFind loops(nv);
    for (int h : boundary) loops.unite(origin(h), origin(hnext(h)));
    std::vector<std::int64_t> length(nv, 0);
    for (int h : boundary) ++length[loops.find(origin(h))];
    Collector bl;
    for (int h : boundary) {  // boundary is in edge-key order: deterministic
      const int root = loops.find(origin(h));
      if (length[root] == 0) continue;  // loop already reported
      const int u = origin(h), w = origin(hnext(h));
      bl.add(a.tri_face[h / 3], !bl.named() ? std::string()
                                            : "a loop of " + plural(length[root], "edge", "edges") + " through edge (" +
                                                  std::to_string(u) + ", " + std::to_string(w) + ") of face " +
                                                  std::to_string(a.tri_face[h / 3]));
      length[root] = 0;
    }
    r.boundary_loops = bl.count;
    emit(ErrorKind::Boundary, bl,
         "the surface is not closed: " + plural(bl.count, "boundary loop", "boundary loops") + " (" +
             plural(r.boundary_edges, "edge", "edges") + " with one face): " + bl.list());
  }

  // --- 12: components through shared vertices (kept unreferenced vertices are their own) ---
  {
    UnionFind comp(nv);
    for (const auto& t : a.tris) {
      comp.unite(t[0], t[1]);
      comp.unite(t[0], t[2]);
    }
    std::vector<std::int64_t> first_face(nv, -1), tri_count(nv, 0);
    for (std::size_t t = 0; t < T; ++t) {
      const int root = comp.find(a.tris[t][0]);
      if (first_face[root] < 0) first_face[root] = a.tri_face[t];
      ++tri_count[root];
    }
    Collector cc;
    for (std::size_t v = 0; v < nv; ++v)
      if (a.keep_vertex[v] && comp.find(int(v)) == int(v)) {
        if (first_face[v] >= 0)
          cc.add(first_face[v],
                 plural(tri_count[v], "triangle", "triangles") + " from face " + std::to_string(first_face[v]));
        else
          cc.add_without_id("unreferenced vertex " + std::to_string(v));
      }
    r.components = cc.count;
    if (cc.count > 1)
      emit(ErrorKind::SeveralComponents, cc,
           "the mesh has " + std::to_string(cc.count) + " connected components: " + cc.list());
  }

  if (r.unreferenced_vertices > 0 && opt.drop_unreferenced) {
    std::vector<std::int64_t> unused;
    for (std::size_t v = 0; v < nv && unused.size() <= kMaxNamed; ++v)
      if (!referenced[v]) unused.push_back(static_cast<std::int64_t>(v));
    r.warnings.push_back("dropped " + plural(r.unreferenced_vertices, "unreferenced vertex", "unreferenced vertices") +
                         " (" + ids_text(unused) + ")");
  }

  std::int64_t kept = 0;
  for (char k : a.keep_vertex) kept += k;
  r.euler_characteristic = kept - r.edges + static_cast<std::int64_t>(T);
  if (r.problems.empty()) r.genus = static_cast<int>((2 - r.euler_characteristic) / 2);
  if (surfaces) {
    a.corner_class.resize(3 * T);
    for (std::size_t h = 0; h < 3 * T; ++h) a.corner_class[h] = corners.find(int(h));
  }
  return a;
}

}  // namespace validate_internal

using validate_internal::analyze;
using validate_internal::Mode;

MeshReport inspect(const PolygonSoup& soup, const ValidateOptions& options) {
  return analyze(soup, options, Mode::Closed).report;
}

ValidMesh validate(const PolygonSoup& soup, const ValidateOptions& options) {
  validate_internal::Analysis a = analyze(soup, options, Mode::Closed);
  if (!a.report.problems.empty()) {
    const MeshProblem& p = a.report.problems.front();
    throw Error(p.kind, p.message, p.elements);
  }
  ValidMesh out;
  const std::size_t nv = soup.positions.size();
  std::vector<int> new_id(nv, -1);
  for (std::size_t v = 0; v < nv; ++v)
    if (a.keep_vertex[v]) {
      new_id[v] = static_cast<int>(out.positions.size());
      out.positions.push_back(soup.positions[v]);
      out.input_vertex.push_back(static_cast<std::int64_t>(v));
    }
  std::vector<std::array<int, 3>> tris(a.tris.size());
  for (std::size_t t = 0; t < a.tris.size(); ++t) {
    const auto& s = a.tris[t];
    tris[t] = a.flip[t] ? std::array<int, 3>{new_id[s[0]], new_id[s[2]], new_id[s[1]]}
                        : std::array<int, 3>{new_id[s[0]], new_id[s[1]], new_id[s[2]]};
  }
  out.mesh = TriMesh::from_triangles(static_cast<int>(out.positions.size()), tris);
  const std::string broken = out.mesh.check_invariants();
  if (!broken.empty()) throw Error(ErrorKind::Internal, "validated mesh breaks an invariant: " + broken);
  out.input_face.assign(a.tri_face.begin(), a.tri_face.end());
  out.warnings = a.report.warnings;
  out.genus = a.report.genus;
  return out;
}

ValidMesh load_mesh(const std::filesystem::path& path, const ValidateOptions& options) {
  const PolygonSoup soup = read_soup(path);  // its errors name the path already
  try {
    return validate(soup, options);
  } catch (const Error& e) {
    throw with_path(e, path);
  }
}

}  // namespace igm
