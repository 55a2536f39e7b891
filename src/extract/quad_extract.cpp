#include "igm/extract/quad_extract.h"

#include <map>
#include <string>
#include <tuple>
#include <unordered_map>

#include "igm/core/error.h"

namespace igm {

SidePairing SidePairing::canonical(int genus) {
  SidePairing p;
  for (int i = 0; i < genus; ++i)
    for (int k = 0; k < 4; ++k) {
      p.partner.push_back(4 * i + (k + 2) % 4);
      p.reversed.push_back(1);
    }
  return p;
}

PlanarQuadMesh extract_quads(const QuadTemplate& t, const OverlayResult& ov, const QuadCharts& ch, int N,
                             const SidePairing& pairing) {
  if (N < 1 || N > 4096) throw Error(ErrorKind::InvalidArgument, "extract_quads: resolution must be in 1..4096");
  const int ns = t.num_corners();
  if (static_cast<int>(pairing.partner.size()) != ns || static_cast<int>(pairing.reversed.size()) != ns)
    throw Error(ErrorKind::InvalidArgument, "extract_quads: the side pairing needs one entry per polygon side");
  for (int s = 0; s < ns; ++s) {
    const int p = pairing.partner[s];
    if (p < 0 || p >= ns || p == s || pairing.partner[p] != s || pairing.reversed[p] != pairing.reversed[s])
      throw Error(ErrorKind::InvalidArgument, "extract_quads: side pairing is not a fixed-point-free involution at side " +
                                                  std::to_string(s),
                  {s});
  }
  const auto& F = ov.mesh.triangles;
  const int nf = static_cast<int>(F.size());
  if (static_cast<int>(ch.quad.size()) != nf) throw Error(ErrorKind::InvalidArgument, "extract_quads: charts do not match");
  const int nq = static_cast<int>(t.quads.size());
  std::map<std::pair<int, int>, int> side_of;  // (quad, edge) -> polygon side
  for (int s = 0; s < ns; ++s) side_of[{t.side_quad[s][0], t.side_quad[s][1]}] = s;

  std::vector<std::vector<int>> quad_tris(nq);
  for (int f = 0; f < nf; ++f) quad_tris[ch.quad[f]].push_back(f);

  PlanarQuadMesh out;
  std::map<int, int> layout_id;                              // layout vertex -> quad-mesh vertex
  std::map<std::tuple<int, int, int>, int> edge_point_id;     // (a, b, m) canonical -> quad-mesh vertex
  std::map<std::tuple<int, int, int>, int> edge_piece_id;     // (a, b, r) canonical -> quad-mesh edge
  const Rational invN(1, N);
  for (int q = 0; q < nq; ++q) {
    // The UV triangulation of quad q (local vertex ids).
    std::unordered_map<int, int> local;
    std::vector<Point2q> uv;
    std::vector<std::array<int, 3>> lt;
    for (int f : quad_tris[q]) {
      std::array<int, 3> L{};
      for (int i = 0; i < 3; ++i) {
        auto [it, fresh] = local.emplace(F[f][i], static_cast<int>(uv.size()));
        if (fresh) uv.push_back(ch.uv[f][i]);
        L[i] = it->second;
      }
      lt.push_back(L);
    }
    if (lt.empty()) throw Error(ErrorKind::Internal, "extract_quads: layout quad " + std::to_string(q) + " has no triangle", {q});
    const PlanarAdjacency adj = PlanarAdjacency::build(static_cast<int>(uv.size()), lt);
    const auto& Q = t.quads[q];
    int from = lt[0][0];
    auto locate = [&](const Point2q& target) {
      QuadVertexLocation v;
      const PlanarLocation loc = locate_point(uv, lt, adj, from, target);
      const auto& L = lt[loc.triangle];
      v.triangle = quad_tris[q][loc.triangle];
      v.barycentric = {0, 0, 0};
      if (loc.kind == PlanarLocation::Kind::Vertex) {
        v.barycentric[loc.index] = 1;
      } else if (loc.kind == PlanarLocation::Kind::Edge) {
        const int i = loc.index, j = (i + 1) % 3;
        const Rational s = dot(uv[L[i]], target, uv[L[j]]) / dot(uv[L[i]], uv[L[j]], uv[L[j]]);
        v.barycentric[i] = 1 - s;
        v.barycentric[j] = s;
      } else {
        const Point2q &A = uv[L[0]], &B = uv[L[1]], &C = uv[L[2]];
        const Rational area = cross(A, B, C);
        v.barycentric = {cross(target, B, C) / area, cross(A, target, C) / area, cross(A, B, target) / area};
      }
      const auto& T = F[v.triangle];
      v.position = {0, 0};
      for (int i = 0; i < 3; ++i) {
        v.position.x += v.barycentric[i] * ov.mesh.positions[T[i]].x;
        v.position.y += v.barycentric[i] * ov.mesh.positions[T[i]].y;
      }
      from = L[0];
      return v;
    };
    auto add_vertex = [&](QuadVertexLocation v) {
      out.vertices.push_back(std::move(v));
      return static_cast<int>(out.vertices.size()) - 1;
    };
    std::vector<int> grid((N + 1) * (N + 1), -1);
    for (int j = 0; j <= N; ++j)
      for (int ii = 0; ii <= N; ++ii) {
        const int i = (j % 2 == 0) ? ii : N - ii;  // snake order keeps walks short
        const Point2q target{Rational(i * invN), Rational(j * invN)};
        const bool bi = i == 0 || i == N, bj = j == 0 || j == N;
        int id = -1;
        if (bi && bj) {  // a corner of the quad: its layout vertex
          const int k = (j == 0) ? (i == 0 ? 0 : 1) : (i == N ? 2 : 3);
          const int lv = t.layout_vertex[Q[k]];
          auto it = layout_id.find(lv);
          if (it != layout_id.end()) {
            id = it->second;
          } else {
            QuadVertexLocation v = locate(target);
            v.layout_vertex = lv;
            id = add_vertex(std::move(v));
            layout_id.emplace(lv, id);
          }
        } else if (bi || bj) {  // on quad edge k at parameter m/N from Q_k
          int k = 0, m = 0;
          if (j == 0) k = 0, m = i;
          else if (i == N) k = 1, m = j;
          else if (j == N) k = 2, m = N - i;
          else k = 3, m = N - j;
          int a = Q[k], b = Q[(k + 1) % 4];
          auto sit = side_of.find({q, k});
          if (sit != side_of.end()) {  // a polygon side: use the lower of the two glued sides
            const int s = sit->second, p = pairing.partner[s];
            if (p < s) {
              if (pairing.reversed[s]) m = N - m;
              a = p, b = (p + 1) % ns;
            }
          }
          if (a > b) std::swap(a, b), m = N - m;
          const auto key = std::make_tuple(a, b, m);
          auto it = edge_point_id.find(key);
          if (it != edge_point_id.end()) {
            id = it->second;
          } else {
            id = add_vertex(locate(target));
            edge_point_id.emplace(key, id);
          }
        } else {
          id = add_vertex(locate(target));
        }
        grid[j * (N + 1) + i] = id;
      }
    // Edge ids: sub-edge r (params r/N..(r+1)/N from Q_k) of quad edge k is shared through the
    // same canonical key as the vertices; inner grid edges are new.
    auto boundary_edge = [&](int k, int r) {
      int a = Q[k], b = Q[(k + 1) % 4];
      auto sit = side_of.find({q, k});
      if (sit != side_of.end()) {
        const int s = sit->second, p = pairing.partner[s];
        if (p < s) {
          if (pairing.reversed[s]) r = N - 1 - r;
          a = p, b = (p + 1) % ns;
        }
      }
      if (a > b) std::swap(a, b), r = N - 1 - r;
      auto [it, fresh] = edge_piece_id.emplace(std::make_tuple(a, b, r), out.num_edges);
      if (fresh) ++out.num_edges;
      return it->second;
    };
    std::vector<int> H((N + 1) * N), V((N + 1) * N);  // H[j*N+i]: (i,j)-(i+1,j); V[j*(N+1)+i]: (i,j)-(i,j+1)
    for (int j = 0; j <= N; ++j)
      for (int i = 0; i < N; ++i)
        H[j * N + i] = j == 0 ? boundary_edge(0, i) : (j == N ? boundary_edge(2, N - 1 - i) : out.num_edges++);
    for (int j = 0; j < N; ++j)
      for (int i = 0; i <= N; ++i)
        V[j * (N + 1) + i] = i == N ? boundary_edge(1, j) : (i == 0 ? boundary_edge(3, N - 1 - j) : out.num_edges++);
    for (int j = 0; j < N; ++j)
      for (int i = 0; i < N; ++i) {
        out.quad_edges.push_back({H[j * N + i], V[j * (N + 1) + i + 1], H[(j + 1) * N + i], V[j * (N + 1) + i]});
        out.quads.push_back({grid[j * (N + 1) + i], grid[j * (N + 1) + i + 1], grid[(j + 1) * (N + 1) + i + 1],
                             grid[(j + 1) * (N + 1) + i]});
        out.layout_quad.push_back(q);
      }
  }
  return out;
}

}  // namespace igm
