#include "igm/igm/layout_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <map>
#include <string>
#include <utility>

#include "../core/parallel.h"
#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/mesh/scale.h"

namespace igm {

namespace {

std::string str(std::int64_t x) { return std::to_string(x); }

constexpr int kCornerX[4] = {0, 1, 1, 0}, kCornerY[4] = {0, 0, 1, 1};
constexpr int kDirX[4] = {1, 0, -1, 0}, kDirY[4] = {0, 1, 0, -1};

// What every patch's map reads; nothing in it is written while the patches are mapped.
struct Shared {
  const SurfaceLayout& L;
  const LayoutAdjacency& A;
  const std::vector<int>& length;                  // per arc
  const std::vector<std::vector<Rational>>& param;  // per arc, forward
  const std::vector<Vec3d>& input_positions;
  const LayoutMapOptions& options;
};

// One patch's map: its triangles (the disk's, in place, then the splits' second halves), their
// vertices (surface ids, or -1 - j for the j-th split vertex of this patch) and corner UVs.
struct PatchResult {
  std::vector<int> triangles;  // global ids of the disk's triangles (the first local_triangles)
  std::vector<std::array<int, 3>> local_triangles;
  std::vector<int> vertex;                   // local -> surface vertex, or -1 - j for new vertex j
  std::vector<SurfacePoint> new_locations;   // the splits' midpoints
  std::vector<std::array<Point2q, 3>> uv;    // per local triangle
  TutteStats tutte;
  int splits = 0;
};

std::uint64_t pair_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b))) << 32) |
         static_cast<std::uint32_t>(std::max(a, b));
}

// Splits every interior edge of the disk whose two ends lie on one side (mask bits in common).
// Each split makes an interior vertex whose edges all end at it, so no split makes another one
// necessary: one pass over the initial candidates, in the order of their vertex pairs.
void split_same_side_edges(PatchResult& r, std::vector<int>& mask, const Shared& s) {
  std::map<std::uint64_t, std::array<int, 2>> edge_tris;  // local edge -> its (one or two) triangles
  for (std::size_t t = 0; t < r.local_triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = r.local_triangles[t][i], b = r.local_triangles[t][(i + 1) % 3];
      if (!(mask[a] & mask[b])) continue;
      auto [it, fresh] = edge_tris.emplace(pair_key(a, b), std::array<int, 2>{static_cast<int>(t), -1});
      if (!fresh) it->second[1] = static_cast<int>(t);
    }
  std::vector<std::uint64_t> chords;
  for (const auto& [key, tris] : edge_tris)
    if (tris[1] >= 0) chords.push_back(key);  // two triangles: an interior edge of the disk (ascending keys)
  if (chords.empty()) return;
  // Every edge of the triangles that a split may move must be found again: index them all.
  std::map<std::uint64_t, std::array<int, 2>> all;
  for (std::size_t t = 0; t < r.local_triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      auto [it, fresh] = all.emplace(pair_key(r.local_triangles[t][i], r.local_triangles[t][(i + 1) % 3]),
                                     std::array<int, 2>{static_cast<int>(t), -1});
      if (!fresh) it->second[1] = static_cast<int>(t);
    }
  auto location = [&](int local) -> const SurfacePoint& {
    const int v = r.vertex[local];
    return v >= 0 ? s.L.locations[v] : r.new_locations[-1 - v];
  };
  for (std::uint64_t key : chords) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    const std::array<int, 2> tris = all.at(key);
    const int mid = static_cast<int>(r.vertex.size());
    SurfacePoint p;
    lerp_into(p, location(a), location(b), Rational(1, 2));
    r.vertex.push_back(-1 - static_cast<int>(r.new_locations.size()));
    r.new_locations.push_back(std::move(p));
    mask.push_back(0);
    for (int t : tris) {
      auto& T = r.local_triangles[t];
      int i = 0;
      while (!((T[i] == a && T[(i + 1) % 3] == b) || (T[i] == b && T[(i + 1) % 3] == a))) ++i;  // < 3 steps
      const int u = T[i], w = T[(i + 1) % 3], x = T[(i + 2) % 3];
      const int second = static_cast<int>(r.local_triangles.size());
      T = {u, mid, x};
      r.local_triangles.push_back({mid, w, x});
      // (w, x) moved to `second`; the new edges (mid, *) are indexed too: a later split of a chord
      // of these triangles finds them as its third side (regression: elk, alignment 0).
      auto& wx = all.at(pair_key(w, x));
      if (wx[0] == t) wx[0] = second;
      else if (wx[1] == t) wx[1] = second;
      auto add = [&](int p0, int p1, int tri) {
        auto [it, fresh] = all.emplace(pair_key(p0, p1), std::array<int, 2>{tri, -1});
        if (!fresh) it->second[1] = tri;
      };
      add(u, mid, t);
      add(mid, x, t);
      add(mid, x, second);
      add(mid, w, second);
    }
    ++r.splits;
  }
}

PatchResult map_patch(int p, const Shared& s) {
  const SurfaceLayout& L = s.L;
  PatchDisk d = patch_disk(L, s.A, p);
  if (!d.error.empty()) throw Error(ErrorKind::Internal, "map_layout: " + d.error, {p});
  PatchResult r;
  r.triangles = std::move(d.triangles);
  r.local_triangles = std::move(d.local_triangles);
  r.vertex = std::move(d.vertex);
  const LayoutPatch& P = L.patches[p];
  int side_length[4] = {0, 0, 0, 0};
  for (int k = 0; k < 4; ++k)
    for (const ArcUse& u : P.sides[k]) side_length[k] += s.length[u.arc];
  const int a = side_length[0], b = side_length[1];
  // The rectangle's boundary: corner k, then side k's arcs on their integer segments.
  std::vector<Point2q> boundary_uv;
  boundary_uv.reserve(d.boundary.size());
  std::vector<int> mask(r.vertex.size(), 0);
  for (int k = 0; k < 4; ++k) {
    const Point2q R{Rational(kCornerX[k] * a), Rational(kCornerY[k] * b)};
    int offset = 0;
    for (const ArcUse& u : P.sides[k]) {
      const std::vector<Rational>& t = s.param[u.arc];
      const int l = s.length[u.arc];
      const std::size_t n = t.size() - 1;
      for (std::size_t i = 0; i < n; ++i) {
        const Rational tau = u.forward ? t[i] : Rational(1 - t[n - i]);
        const Rational step = tau * l + offset;
        boundary_uv.push_back({Rational(R.x + kDirX[k] * step), Rational(R.y + kDirY[k] * step)});
      }
      offset += l;
    }
  }
  for (int k = 0; k < 4; ++k) {
    const int end = k < 3 ? d.corner[k + 1] : static_cast<int>(d.boundary.size());
    for (int j = d.corner[k]; j < end; ++j) mask[d.boundary[j]] |= 1 << k;
    mask[d.boundary[d.corner[k]]] |= 1 << ((k + 3) % 4);  // a corner lies on the side before it too
  }
  split_same_side_edges(r, mask, s);
  const LayoutMapOptions& o = s.options;
  std::vector<Vec3d> pos(r.vertex.size());
  for (std::size_t i = 0; i < r.vertex.size(); ++i) {
    const int v = r.vertex[i];
    const Vec3d q = v >= 0 ? L.positions[v] : evaluate(r.new_locations[-1 - v], s.input_positions);
    pos[i] = {o.length_scale * q.x, o.length_scale * q.y, o.length_scale * q.z};
  }
  const std::vector<int> w = edge_weights(pos, r.local_triangles, o.weights);
  TutteResult tr = tutte_embed(static_cast<int>(r.vertex.size()), r.local_triangles, d.boundary, boundary_uv, w, o.tutte);
  r.tutte = std::move(tr.stats);
  r.uv.resize(r.local_triangles.size());
  for (std::size_t k = 0; k < r.local_triangles.size(); ++k)
    for (int i = 0; i < 3; ++i) r.uv[k][i] = tr.uv[r.local_triangles[k][i]];
  return r;
}

}  // namespace

LayoutMap map_layout(SurfaceLayout L, const std::vector<int>& length, const LayoutMapOptions& options) {
  const auto t_start = std::chrono::steady_clock::now();
  if (options.parameter_bits < 1 || options.parameter_bits > 52)
    throw Error(ErrorKind::InvalidArgument, "map_layout: parameter_bits must be in 1..52");
  if (!(options.length_scale > 0) || !std::isfinite(options.length_scale))
    throw Error(ErrorKind::InvalidArgument, "map_layout: length_scale must be positive and finite");
  if (const std::string e = check_surface_layout(L); !e.empty())
    throw Error(ErrorKind::InvalidArgument, "map_layout: the layout is not valid: " + e);
  const int na = static_cast<int>(L.arcs.size()), np = static_cast<int>(L.patches.size());
  if (static_cast<int>(length.size()) != na)
    throw Error(ErrorKind::InvalidArgument, "map_layout: one length per arc is needed");
  for (int a = 0; a < na; ++a)
    if (length[a] < 1 || length[a] > (1 << 20))
      throw Error(ErrorKind::InvalidArgument, "map_layout: arc " + str(a) + " has length " + str(length[a]) + ", not in 1..2^20",
                  {a});
  LayoutMap out;
  out.patch_size.resize(np);
  for (int p = 0; p < np; ++p) {
    std::int64_t side[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (const ArcUse& u : L.patches[p].sides[k]) side[k] += length[u.arc];
    if (side[0] != side[2] || side[1] != side[3])
      throw Error(ErrorKind::InvalidArgument, "map_layout: patch " + str(p) + "'s opposite sides have lengths " + str(side[0]) +
                                                  " and " + str(side[2]) + ", " + str(side[1]) + " and " + str(side[3]),
                  {p});
    if (side[0] > (1 << 20) || side[1] > (1 << 20))
      throw Error(ErrorKind::InvalidArgument, "map_layout: patch " + str(p) + " is longer than 2^20", {p});
    out.patch_size[p] = {static_cast<int>(side[0]), static_cast<int>(side[1])};
  }
  const LayoutAdjacency A = layout_adjacency(L);
  std::vector<std::vector<Rational>> param(na);
  for (int a = 0; a < na; ++a) {
    const auto& V = L.arcs[a].vertices;
    std::vector<double> len(V.size() - 1);
    for (std::size_t k = 0; k + 1 < V.size(); ++k)
      len[k] = scaled_distance(L.positions[V[k]], L.positions[V[k + 1]], options.length_scale);
    param[a] = arc_length_parameters(len, options.parameter_bits);
  }
  const std::vector<Vec3d> input_positions(L.positions.begin(), L.positions.begin() + L.num_input_vertices);
  const Shared shared{L, A, length, param, input_positions, options};
  // The patches are independent: mapped in parallel, each into its own slot; the first failing
  // patch's error (in patch order) is thrown, so nothing depends on the thread count.
  std::vector<PatchResult> results(np);
  std::vector<std::exception_ptr> failure(np);
  parallel::for_each_index(np, 1, [&](std::int64_t p) {
    try {
      results[p] = map_patch(static_cast<int>(p), shared);
    } catch (...) {
      failure[p] = std::current_exception();
    }
  });
  for (int p = 0; p < np; ++p)
    if (failure[p]) std::rethrow_exception(failure[p]);

  // --- assembly, patch by patch: split vertices and second halves appended ---
  PatchMapStats& st = out.stats;
  st.patches = np;
  const int nv0 = static_cast<int>(L.locations.size()), nf0 = static_cast<int>(L.triangles.size());
  std::vector<int> vertex_base(np + 1, nv0), triangle_base(np + 1, nf0);
  for (int p = 0; p < np; ++p) {
    const PatchResult& r = results[p];
    vertex_base[p + 1] = vertex_base[p] + static_cast<int>(r.new_locations.size());
    triangle_base[p + 1] = triangle_base[p] + static_cast<int>(r.local_triangles.size() - r.triangles.size());
  }
  IgmMesh& igm = out.igm;
  igm.locations = std::move(L.locations);
  igm.positions = std::move(L.positions);
  igm.triangles = std::move(L.triangles);
  out.triangle_patch = std::move(L.triangle_patch);
  igm.locations.resize(vertex_base[np]);
  igm.positions.resize(vertex_base[np]);
  igm.triangles.resize(triangle_base[np]);
  out.triangle_patch.resize(triangle_base[np]);
  igm.corner_uv.resize(triangle_base[np]);
  for (int p = 0; p < np; ++p) {
    PatchResult& r = results[p];
    const TutteStats& ts = r.tutte;
    st.max_patch_vertices = std::max(st.max_patch_vertices, static_cast<int>(r.vertex.size()));
    st.flips_double += ts.flips_double;
    if (ts.iterations > 0) ++st.patches_refined;
    st.max_refinement_steps = std::max(st.max_refinement_steps, ts.iterations);
    st.max_uv_bits = std::max(st.max_uv_bits, ts.max_bits);
    st.splits += r.splits;
    for (std::size_t j = 0; j < r.new_locations.size(); ++j) {
      igm.positions[vertex_base[p] + j] = evaluate(r.new_locations[j], input_positions);
      igm.locations[vertex_base[p] + j] = std::move(r.new_locations[j]);
    }
    const std::size_t n = r.triangles.size();
    for (std::size_t k = 0; k < r.local_triangles.size(); ++k) {
      const int t = k < n ? r.triangles[k] : triangle_base[p] + static_cast<int>(k - n);
      for (int i = 0; i < 3; ++i) {
        const int v = r.vertex[r.local_triangles[k][i]];
        igm.triangles[t][i] = v >= 0 ? v : vertex_base[p] + (-1 - v);
      }
      igm.corner_uv[t] = std::move(r.uv[k]);
      out.triangle_patch[t] = p;
    }
    r = PatchResult{};
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  return out;
}

}  // namespace igm
