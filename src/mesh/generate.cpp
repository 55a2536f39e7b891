#include "igm/mesh/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "igm/core/error.h"

namespace igm {

PolygonSoup generate_closed_mesh(const GenerateOptions& o) {
  if (o.genus < 0 || o.genus > 100000)
    throw Error(ErrorKind::InvalidArgument, "genus must be in 0..100000, got " + std::to_string(o.genus));
  if (o.faces < 0 || o.faces > (std::int64_t{1} << 28))
    throw Error(ErrorKind::InvalidArgument, "faces must be in 0..2^28, got " + std::to_string(o.faces));
  if (!(o.jitter >= 0.0 && o.jitter < 0.5))
    throw Error(ErrorKind::InvalidArgument, "jitter must be in [0, 0.5)");
  std::mt19937_64 rng(o.seed);

  // Macro layout: (2A+1) x (2B+1) macro cells, holes at odd positions, A*B >= genus.
  const int g = o.genus;
  int A = 0, B = 0;
  if (g > 0) {
    A = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(g))));
    B = (g + A - 1) / A;
  }
  const std::int64_t macro_cells = std::int64_t(2 * A + 1) * (2 * B + 1) - g;
  // Each small cell gives 2 triangles per sheet, 2 sheets; s >= 2 keeps boundary vertices apart.
  int s = static_cast<int>(std::lround(std::sqrt(static_cast<double>(o.faces) / (4.0 * macro_cells))));
  s = std::max(s, 2);
  const int W = (2 * A + 1) * s, H = (2 * B + 1) * s;

  auto is_hole = [&](int i, int j) {  // small cell (i, j)
    int mi = i / s, mj = j / s;
    if (mi % 2 == 0 || mj % 2 == 0) return false;
    int a = mi / 2, b = mj / 2;
    return b * A + a < g;
  };
  auto cell_in = [&](int i, int j) { return i >= 0 && j >= 0 && i < W && j < H && !is_hole(i, j); };
  // Grid vertex (i, j), 0 <= i <= W, 0 <= j <= H, is used if a neighbouring cell is in the
  // region, and on the boundary if some neighbouring cell is not.
  const int NV = (W + 1) * (H + 1);
  auto gid = [&](int i, int j) { return j * (W + 1) + i; };
  std::vector<int> top(NV, -1), bottom(NV, -1);
  PolygonSoup soup;
  std::uniform_real_distribution<double> jit(-o.jitter, o.jitter);
  std::vector<char> boundary(NV, 0);
  for (int j = 0; j <= H; ++j)
    for (int i = 0; i <= W; ++i) {
      int in = 0;
      for (int dj = -1; dj <= 0; ++dj)
        for (int di = -1; di <= 0; ++di) in += cell_in(i + di, j + dj);
      if (in == 0) continue;
      boundary[gid(i, j)] = in < 4;
      double x = i, y = j;
      if (in == 4) {
        x += jit(rng);
        y += jit(rng);
      }
      if (in < 4) {
        top[gid(i, j)] = bottom[gid(i, j)] = static_cast<int>(soup.positions.size());
        soup.positions.push_back({x, y, 0.0});
      } else {
        top[gid(i, j)] = static_cast<int>(soup.positions.size());
        soup.positions.push_back({x, y, 1.0 + 0.1 * jit(rng)});
        bottom[gid(i, j)] = static_cast<int>(soup.positions.size());
        soup.positions.push_back({x, y, -1.0 + 0.1 * jit(rng)});
      }
    }
  std::bernoulli_distribution coin(0.5);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      if (!cell_in(i, j)) continue;
      const int c00 = gid(i, j), c10 = gid(i + 1, j), c11 = gid(i + 1, j + 1), c01 = gid(i, j + 1);
      // Diagonal 00-11 or 10-01: never one joining two boundary vertices (with s >= 2 one of
      // the two always qualifies: a cell has at most three boundary corners, and then the
      // fourth is opposite one of them).
      bool ok_a = !(boundary[c00] && boundary[c11]);
      bool ok_b = !(boundary[c10] && boundary[c01]);
      if (!ok_a && !ok_b) throw Error(ErrorKind::Internal, "generator: cell with both diagonals on the boundary");
      bool diag_a = ok_a && (!ok_b || coin(rng));
      std::array<std::array<int, 3>, 2> tris;
      if (diag_a)
        tris = {{{c00, c10, c11}, {c00, c11, c01}}};
      else
        tris = {{{c00, c10, c01}, {c10, c11, c01}}};
      for (const auto& t : tris) {
        soup.add_face({top[t[0]], top[t[1]], top[t[2]]});
        soup.add_face({bottom[t[0]], bottom[t[2]], bottom[t[1]]});
      }
    }
  if (!o.shuffle) return soup;

  // Random relabelling: vertex permutation, face order, and a rotation of each face's corners.
  const std::size_t nv = soup.positions.size(), nf = soup.num_faces();
  std::vector<std::int64_t> perm(nv);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<Vec3d> pos(nv);
  for (std::size_t v = 0; v < nv; ++v) pos[perm[v]] = soup.positions[v];
  std::vector<std::size_t> order(nf);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  PolygonSoup out;
  out.positions = std::move(pos);
  out.corners.reserve(soup.corners.size());
  out.face_begin.reserve(nf + 1);
  std::uniform_int_distribution<int> rot(0, 2);
  for (std::size_t f : order) {
    const std::int64_t* c = &soup.corners[soup.face_begin[f]];
    int r = rot(rng);
    out.add_face({perm[c[r]], perm[c[(r + 1) % 3]], perm[c[(r + 2) % 3]]});
  }
  return out;
}

}  // namespace igm
