#include "igm/mesh/generate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

// A square hole: k x k cells from cell (i, j) of one sheet (0 top, 1 bottom).
struct Hole {
  int sheet, i, j;
};

// Chooses `count` holes (see generate.h): squares of cells that are all `good` (in the region,
// no seam corner), on a lattice of pitch k + max(2, k) with the offset (o, o) that fits the most,
// for the largest k <= max(1, min(W, H) / 16) that fits `count` (two sheets). Returns them with
// k. Cost O(W H) per k tried: O(W H log(min(W, H))) in all (the lattice has W H / p^2 positions
// per offset, p offsets).
std::pair<std::vector<Hole>, int> choose_holes(const std::vector<char>& good, int W, int H,
                                               int count, std::uint64_t seed, int genus,
                                               std::int64_t faces) {
  // prefix[(j)(W+1) + i]: good cells in [0, i) x [0, j)
  std::vector<std::int32_t> prefix(static_cast<std::size_t>(W + 1) * (H + 1), 0);
  auto at = [&](int i, int j) -> std::int32_t& {
    return prefix[static_cast<std::size_t>(j) * (W + 1) + i];
  };
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i)
      at(i + 1, j + 1) =
          at(i, j + 1) + at(i + 1, j) - at(i, j) + good[static_cast<std::size_t>(j) * W + i];
  auto fits = [&](int i, int j, int k) {
    return i + k <= W && j + k <= H &&
           at(i + k, j + k) - at(i, j + k) - at(i + k, j) + at(i, j) == k * k;
  };
  int capacity = 0;  // at k = 1, for the message
  for (int k = std::max(1, std::min(W, H) / 16); k >= 1; --k) {
    const int p = k + std::max(2, k);
    int best = -1, best_offset = 0;
    for (int off = 0; off < p; ++off) {
      int n = 0;
      for (int j = off; j < H; j += p)
        for (int i = off; i < W; i += p) n += fits(i, j, k);
      if (n > best) best = n, best_offset = off;
    }
    if (k == 1) capacity = 2 * best;
    if (2 * best < count) continue;
    std::vector<Hole> all;
    for (int sheet = 0; sheet < 2; ++sheet)
      for (int j = best_offset; j < H; j += p)
        for (int i = best_offset; i < W; i += p)
          if (fits(i, j, k)) all.push_back({sheet, i, j});
    std::mt19937_64 rng(seed ^ 0x9e3779b97f4a7c15ull);  // its own stream: the mesh's is untouched
    std::shuffle(all.begin(), all.end(), rng);
    all.resize(static_cast<std::size_t>(count));
    return {all, k};
  }
  throw Error(ErrorKind::InvalidArgument,
              std::to_string(count) + (count == 1 ? " boundary loop does" : " boundary loops do") +
                  " not fit a generated mesh of genus " + std::to_string(genus) + " and about " +
                  std::to_string(faces) + " faces: at most " + std::to_string(capacity) +
                  " well-separated holes (more faces make room)");
}

}  // namespace

PolygonSoup generate_closed_mesh(const GenerateOptions& o) {
  if (o.boundaries != 0)
    throw Error(ErrorKind::InvalidArgument,
                "generate_closed_mesh makes closed meshes: boundaries must be 0, got " +
                    std::to_string(o.boundaries));
  return generate_mesh(o);
}

PolygonSoup generate_mesh(const GenerateOptions& o) {
  if (o.genus < 0 || o.genus > 100000)
    throw Error(ErrorKind::InvalidArgument, "genus must be in 0..100000, got " + std::to_string(o.genus));
  if (o.boundaries < 0 || o.boundaries > 100000)
    throw Error(ErrorKind::InvalidArgument,
                "boundaries must be in 0..100000, got " + std::to_string(o.boundaries));
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
  // Holes: removed[sheet][cell]. The coins below are drawn for removed cells too, so that the
  // mesh with holes is the closed one without their faces.
  std::array<std::vector<char>, 2> removed;
  if (o.boundaries > 0) {
    std::vector<char> good(static_cast<std::size_t>(W) * H, 0);
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i)
        good[static_cast<std::size_t>(j) * W + i] =
            cell_in(i, j) && !boundary[gid(i, j)] && !boundary[gid(i + 1, j)] &&
            !boundary[gid(i, j + 1)] && !boundary[gid(i + 1, j + 1)];
    const auto [holes, k] = choose_holes(good, W, H, o.boundaries, o.seed, g, o.faces);
    for (auto& r : removed) r.assign(static_cast<std::size_t>(W) * H, 0);
    for (const Hole& h : holes)
      for (int j = h.j; j < h.j + k; ++j)
        for (int i = h.i; i < h.i + k; ++i)
          removed[h.sheet][static_cast<std::size_t>(j) * W + i] = 1;
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
      const std::size_t cell = static_cast<std::size_t>(j) * W + i;
      const bool keep_top = removed[0].empty() || !removed[0][cell];
      const bool keep_bottom = removed[1].empty() || !removed[1][cell];
      for (const auto& t : tris) {
        if (keep_top) soup.add_face({top[t[0]], top[t[1]], top[t[2]]});
        if (keep_bottom) soup.add_face({bottom[t[0]], bottom[t[2]], bottom[t[1]]});
      }
    }
  if (o.boundaries > 0) {  // drop the vertices inside the holes (renumbered in order)
    std::vector<std::int64_t> id(soup.positions.size(), -1);
    for (std::int64_t v : soup.corners) id[static_cast<std::size_t>(v)] = 0;
    std::vector<Vec3d> kept;
    for (std::size_t v = 0; v < id.size(); ++v)
      if (id[v] == 0) {
        id[v] = static_cast<std::int64_t>(kept.size());
        kept.push_back(soup.positions[v]);
      }
    for (std::int64_t& v : soup.corners) v = id[static_cast<std::size_t>(v)];
    soup.positions = std::move(kept);
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
