#include "igm/embed/orbifold_tutte.h"

#include <algorithm>
#include <cstdint>
#include <chrono>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// How the position of a disk vertex follows from the unknowns: s * x[unknown] + t, or the fixed
// point t when unknown < 0.
struct Chart {
  int unknown = -1;
  int s = 1;
  int tx = 0, ty = 0;
  bool plain() const { return unknown >= 0 && s == 1 && tx == 0 && ty == 0; }
};

}  // namespace

PillowcaseMap pillowcase_transition(int leg) {
  switch (leg) {
    case 0: return {-1, 2, 0};
    case 1: return {1, -2, 0};
    case 2: return {-1, 2, 2};
    default: throw Error(ErrorKind::InvalidArgument, "pillowcase_transition: leg " + std::to_string(leg));
  }
}

std::array<int, 2> pillowcase_corner(int i) {
  static constexpr std::array<std::array<int, 2>, 6> c{{{1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}, {0, 0}}};
  if (i < 0 || i >= 6) throw Error(ErrorKind::InvalidArgument, "pillowcase_corner: corner " + std::to_string(i));
  return c[i];
}

OrbifoldTutteResult orbifold_tutte_embed(const SphereCut& cut, const RefinementOptions& options) {
  return orbifold_tutte_embed(cut, {}, options);
}

OrbifoldTutteResult orbifold_tutte_embed(const SphereCut& cut, const std::vector<int>& weights,
                                         const RefinementOptions& options) {
  const auto t_start = Clock::now();
  OrbifoldTutteResult result;
  OrbifoldTutteStats& st = result.stats;
  const TriMesh& m = cut.surface.mesh;
  const int nv = cut.num_surface_vertices;
  const int nd = static_cast<int>(cut.disk_to_surface.size());
  const int k = static_cast<int>(cut.path.size()) - 1;
  if (nv != m.num_vertices() || nd != nv + k - 1 || k < 3)
    throw Error(ErrorKind::InvalidArgument, "orbifold_tutte_embed: the cut does not match its surface");
  if (!weights.empty() && static_cast<int>(weights.size()) != m.num_halfedges())
    throw Error(ErrorKind::InvalidArgument, "orbifold_tutte_embed: " + std::to_string(weights.size()) +
                                                " weights for " + std::to_string(m.num_halfedges()) + " half-edges");
  const int iB = cut.cone_index[1], iC = cut.cone_index[2];
  if (cut.cone_index[0] != 0 || !(0 < iB && iB < iC && iC < k) || cut.cone_index[3] != k)
    throw Error(ErrorKind::InvalidArgument, "orbifold_tutte_embed: cones not in path order");

  // ---------------- charts of the disk vertices ----------------
  std::vector<Chart> chart(nd);
  std::vector<int> cone_corner(nv, -1);  // cone -> corner of its copy 1
  cone_corner[cut.path[0]] = 0;
  cone_corner[cut.path[iB]] = 1;
  cone_corner[cut.path[iC]] = 2;
  cone_corner[cut.path[k]] = 3;
  int unknowns = 0;
  for (int v = 0; v < nv; ++v) {
    if (cone_corner[v] >= 0) {
      const auto p = pillowcase_corner(cone_corner[v]);
      chart[v] = {-1, 0, p[0], p[1]};
    } else {
      chart[v] = {unknowns++, 1, 0, 0};
    }
  }
  for (int i = 1; i < k; ++i) {
    const int d = cut.copy2(i);
    if (i == iB || i == iC) {
      const auto p = pillowcase_corner(i == iB ? 5 : 4);
      chart[d] = {-1, 0, p[0], p[1]};
    } else {
      const PillowcaseMap t = pillowcase_transition(i < iB ? 0 : (i < iC ? 1 : 2));
      chart[d] = {chart[cut.path[i]].unknown, t.s, t.tx, t.ty};
    }
  }
  st.free_vertices = unknowns;
  st.triangles = static_cast<int>(cut.disk_triangles.size());

  // ---------------- the system: one term per surface edge, in one of its disk copies ----------------
  const auto t_assemble = Clock::now();
  SpdSystem S;
  S.n = unknowns;
  S.magnitude = 2;
  S.diag.assign(unknowns, 0);
  std::vector<std::array<int, 3>> off;  // (row, column, value)
  std::vector<long> bx(unknowns, 0), by(unknowns, 0);
  off.reserve(2 * static_cast<std::size_t>(m.num_edges()));
  for (int h = 0; h < m.num_halfedges(); ++h) {
    const int tw = m.twin(h);
    if (tw < h) continue;  // each edge once
    const auto& tri = cut.disk_triangles[TriMesh::face(h)];
    const Chart& a = chart[tri[h % 3]];
    const Chart& b = chart[tri[(h % 3 + 1) % 3]];
    if (a.unknown < 0 && b.unknown < 0)
      throw Error(ErrorKind::InvalidArgument, "orbifold_tutte_embed: an edge joins two cones",
                  {m.origin(h), m.target(h)});
    int w = 1;
    if (!weights.empty()) {
      w = weights[h];
      if (w < 1 || weights[tw] != w)
        throw Error(ErrorKind::InvalidArgument, "orbifold_tutte_embed: edge (" + std::to_string(m.origin(h)) + ", " +
                                                    std::to_string(m.target(h)) + ") has a non-positive or asymmetric weight",
                    {m.origin(h), m.target(h)});
    }
    // Row of a: w (x_a - s_a s_b x_b) = w s_a (t_b - t_a); symmetric in a and b.
    for (int side = 0; side < 2; ++side) {
      const Chart& p = side == 0 ? a : b;
      const Chart& q = side == 0 ? b : a;
      if (p.unknown < 0) continue;
      if (S.diag[p.unknown] > INT32_MAX - w)
        throw Error(ErrorKind::Unsupported, "orbifold_tutte_embed: the weights around a vertex sum past 2^31",
                    {m.origin(h), m.target(h)});
      S.diag[p.unknown] += w;
      if (q.unknown >= 0) off.push_back({p.unknown, q.unknown, -p.s * q.s * w});
      bx[p.unknown] += static_cast<long>(w) * p.s * (q.tx - p.tx);
      by[p.unknown] += static_cast<long>(w) * p.s * (q.ty - p.ty);
    }
  }
  std::sort(off.begin(), off.end());
  S.xadj.assign(unknowns + 1, 0);
  for (std::size_t i = 0; i < off.size(); ++i) {
    if (i > 0 && off[i][0] == off[i - 1][0] && off[i][1] == off[i - 1][1]) {
      S.val.back() += off[i][2];  // cannot happen without multi-edges; kept exact anyway
      continue;
    }
    S.adj.push_back(off[i][1]);
    S.val.push_back(off[i][2]);
    ++S.xadj[off[i][0] + 1];
  }
  for (int i = 0; i < unknowns; ++i) S.xadj[i + 1] += S.xadj[i];
  for (int i = 0; i < unknowns; ++i)
    if (bx[i] != 0 || by[i] != 0) {
      S.rhs_rows.push_back(i);
      S.rhs_x.emplace_back(bx[i]);
      S.rhs_y.emplace_back(by[i]);
    }
  st.seconds_assemble = since(t_assemble);

  // ---------------- certificate: every disk triangle positive ----------------
  using Mode = RefinementIterate::Mode;
  auto exact_position = [&](const Chart& c, const RefinementIterate& x) {
    if (c.unknown < 0) return Point2q{Rational(c.tx), Rational(c.ty)};
    Point2q p = x.point(c.unknown);
    if (c.s < 0) {
      p.x = -p.x;
      p.y = -p.y;
    }
    p.x += c.tx;
    p.y += c.ty;
    return p;
  };
  auto certificate = [&](const RefinementIterate& x) -> std::int64_t {
    std::int64_t flips = 0;
    GridScratch scratch;
    std::array<mpz_class, 6> g;  // grid coordinates of the three corners
    for (const auto& t : cut.disk_triangles) {
      const Chart &a = chart[t[0]], &b = chart[t[1]], &c = chart[t[2]];
      Sign o;
      if (x.mode == Mode::Double && a.plain() && b.plain() && c.plain()) {
        const std::vector<double>&xd = *x.xd, &yd = *x.yd;
        o = orient2d(Vec2d{xd[a.unknown], yd[a.unknown]}, Vec2d{xd[b.unknown], yd[b.unknown]},
                     Vec2d{xd[c.unknown], yd[c.unknown]});
      } else if (x.mode == Mode::Grid && x.e >= 0) {
        const std::vector<mpz_class>&X = *x.X, &Y = *x.Y;
        if (a.plain() && b.plain() && c.plain()) {
          o = grid_orient(X[a.unknown], Y[a.unknown], X[b.unknown], Y[b.unknown], X[c.unknown], Y[c.unknown],
                          scratch);
        } else {
          const Chart* cs[3] = {&a, &b, &c};
          for (int i = 0; i < 3; ++i) {
            const Chart& ch = *cs[i];
            for (int d = 0; d < 2; ++d) {
              mpz_class& z = g[2 * i + d];
              const long tr = d == 0 ? ch.tx : ch.ty;
              z = tr;
              mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), static_cast<mp_bitcnt_t>(x.e));  // t * 2^e
              if (ch.unknown >= 0) {
                const mpz_class& u = d == 0 ? X[ch.unknown] : Y[ch.unknown];
                if (ch.s > 0)
                  mpz_add(z.get_mpz_t(), z.get_mpz_t(), u.get_mpz_t());
                else
                  mpz_sub(z.get_mpz_t(), z.get_mpz_t(), u.get_mpz_t());
              }
            }
          }
          o = grid_orient(g[0], g[1], g[2], g[3], g[4], g[5], scratch);
        }
      } else {
        o = orient2d(exact_position(a, x), exact_position(b, x), exact_position(c, x));
      }
      if (o != Sign::Positive) ++flips;
    }
    return flips;
  };

  RefinementResult solved = refine_until_certified(
      S, certificate, options, {"orbifold_tutte_embed", "free vertices", "the exact orbifold Tutte solution"});
  st.refinement = std::move(solved.stats);
  const RefinementIterate x = solved.iterate();
  result.uv.resize(nd);
  for (int d = 0; d < nd; ++d) result.uv[d] = exact_position(chart[d], x);
  std::size_t bits = 0;
  for (const Point2q& p : result.uv) bits = std::max({bits, bit_size(p.x), bit_size(p.y)});
  st.max_bits = bits;
  st.seconds_total = since(t_start);
  return result;
}

}  // namespace igm
