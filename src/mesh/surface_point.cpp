#include "igm/mesh/surface_point.h"

#include <algorithm>
#include <string>

#include "igm/core/error.h"

namespace igm {

SurfacePoint SurfacePoint::vertex(int id) {
  SurfacePoint p;
  p.v[0] = id;
  p.w[0] = 1;
  return p;
}

int SurfacePoint::size() const { return v[2] >= 0 ? 3 : (v[1] >= 0 ? 2 : (v[0] >= 0 ? 1 : 0)); }

namespace {
// Adds weight*p into the accumulator (ids kept sorted ascending in the used prefix). A zero
// weight adds nothing, so every used slot of a result has a weight > 0 (weights are >= 0).
void accumulate(SurfacePoint& acc, const SurfacePoint& p, const Rational& weight) {
  if (sgn(weight) == 0) return;
  for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
    if (sgn(p.w[i]) == 0) continue;
    Rational add = p.w[i] * weight;
    int slot = -1;
    for (int j = 0; j < 3; ++j)
      if (acc.v[j] == p.v[i]) slot = j;
    if (slot < 0) {
      int n = acc.size();
      if (n == 3)
        throw Error(ErrorKind::Internal, "surface point combination spans more than three input vertices",
                    {p.v[i]});
      acc.v[n] = p.v[i];
      acc.w[n] = add;
      for (int j = n; j > 0 && acc.v[j] < acc.v[j - 1]; --j) {
        std::swap(acc.v[j], acc.v[j - 1]);
        std::swap(acc.w[j], acc.w[j - 1]);
      }
    } else {
      acc.w[slot] += add;
    }
  }
}
}  // namespace

void combine_into(SurfacePoint& r, const SurfacePoint& a, const Rational& ta, const SurfacePoint& b,
                  const Rational& tb) {
  // The two ascending supports merged, each weight written in its slot (a shared vertex adds its
  // second term through one scratch value): the weights of adding the terms one by one
  // (accumulate), canonical, without its temporaries; every edge split comes through here.
  const bool use_a = sgn(ta) != 0, use_b = sgn(tb) != 0;
  // x * t, with t = 1/2 (every midpoint split) as a shift of the denominator: no gcd. Both give
  // the canonical product.
  const bool half_a = mpq_cmp_ui(ta.get_mpq_t(), 1, 2) == 0, half_b = mpq_cmp_ui(tb.get_mpq_t(), 1, 2) == 0;
  auto times = [](mpq_ptr out, mpq_srcptr x, const Rational& t, bool half) {
    if (half) mpq_div_2exp(out, x, 1);
    else mpq_mul(out, x, t.get_mpq_t());
  };
  int i = 0, j = 0, n = 0;
  auto has_a = [&] {  // skips a's zero weights; true while a has a term left
    while (use_a && i < 3 && a.v[i] >= 0 && sgn(a.w[i]) == 0) ++i;
    return use_a && i < 3 && a.v[i] >= 0;
  };
  auto has_b = [&] {
    while (use_b && j < 3 && b.v[j] >= 0 && sgn(b.w[j]) == 0) ++j;
    return use_b && j < 3 && b.v[j] >= 0;
  };
  for (bool ha = has_a(), hb = has_b(); ha || hb; ha = has_a(), hb = has_b()) {  // <= 6 steps
    const int id = !hb || (ha && a.v[i] < b.v[j]) ? a.v[i] : b.v[j];
    if (n == 3)
      throw Error(ErrorKind::Internal, "surface point combination spans more than three input vertices", {id});
    r.v[n] = id;
    mpq_ptr w = r.w[n].get_mpq_t();
    if (ha && a.v[i] == id) {
      times(w, a.w[i].get_mpq_t(), ta, half_a);
      ++i;
      if (hb && b.v[j] == id) {
        thread_local Rational term;
        times(term.get_mpq_t(), b.w[j].get_mpq_t(), tb, half_b);
        mpq_add(w, w, term.get_mpq_t());
        ++j;
      }
    } else {
      times(w, b.w[j].get_mpq_t(), tb, half_b);
      ++j;
    }
    ++n;
  }
  for (; n < 3; ++n) r.v[n] = -1, r.w[n] = 0;
}

SurfacePoint combine(const SurfacePoint& a, const Rational& ta, const SurfacePoint& b, const Rational& tb) {
  SurfacePoint r;
  combine_into(r, a, ta, b, tb);
  return r;
}

void lerp_into(SurfacePoint& r, const SurfacePoint& a, const SurfacePoint& b, const Rational& t) {
  if (mpq_cmp_ui(t.get_mpq_t(), 1, 2) == 0) {  // a midpoint (most splits): 1 - t is t
    combine_into(r, a, t, b, t);
    return;
  }
  thread_local Rational s;  // 1 - t, its limbs kept from call to call
  s = 1;
  s -= t;
  combine_into(r, a, s, b, t);
}

SurfacePoint lerp(const SurfacePoint& a, const SurfacePoint& b, const Rational& t) {
  SurfacePoint r;
  lerp_into(r, a, b, t);
  return r;
}

SurfacePoint average(const std::vector<SurfacePoint>& points) {
  if (points.empty()) throw Error(ErrorKind::Internal, "average of no surface points");
  SurfacePoint r;
  Rational w = make_rational(1, static_cast<long>(points.size()));
  for (const auto& p : points) accumulate(r, p, w);
  return r;
}

SurfacePoint barycentric_point(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c,
                               const std::array<Rational, 3>& w) {
  const Rational wab = w[0] + w[1];
  if (sgn(wab) == 0) return c;
  const SurfacePoint ab = combine(a, Rational(w[0] / wab), b, Rational(w[1] / wab));
  return combine(ab, wab, c, w[2]);
}

Vec3d evaluate(const SurfacePoint& p, const std::vector<Vec3d>& pos) {
  if (p.size() == 1) return pos[p.v[0]];  // weight 1 (convex combination): the input position itself
  std::array<Rational, 3> exact;  // sum of w_i * pos_i per coordinate, exactly
  Rational term;
  for (int i = 0; i < 3 && p.v[i] >= 0; ++i) {
    const Vec3d& q = pos[p.v[i]];
    const double c[3] = {q.x, q.y, q.z};
    for (int k = 0; k < 3; ++k) {
      term = to_rational(c[k]);
      term *= p.w[i];
      exact[k] += term;
    }
  }
  return {to_double(exact[0]), to_double(exact[1]), to_double(exact[2])};
}

int RefinedSurface::split_edge(int h, const Rational& t) {
  // The ends are read in place (point() would copy a constructed one).
  const int a = mesh.origin(h), b = mesh.target(h);
  // The point is made in scratch values kept from call to call (their limbs stay allocated) and
  // copied into its new slot: no temporaries to allocate, move and free per split.
  thread_local SurfacePoint ia = SurfacePoint::vertex(0), ib = SurfacePoint::vertex(0), p;
  ia.v[0] = a, ib.v[0] = b;  // an input end's weight-1 point
  lerp_into(p, a < num_input_vertices ? ia : constructed[a - num_input_vertices],
            b < num_input_vertices ? ib : constructed[b - num_input_vertices], t);
  int v = mesh.split_edge(h);
  if (v != num_input_vertices + static_cast<int>(constructed.size()))
    throw Error(ErrorKind::Internal, "refined surface out of step with its mesh", {v});
  constructed.emplace_back();
  SurfacePoint& q = constructed.back();
  q.v = p.v;
  for (int i = 0; i < 3; ++i)
    if (p.v[i] >= 0) q.w[i] = p.w[i];
  return v;
}

int RefinedSurface::split_face(int f) {
  auto c = mesh.face_vertices(f);
  SurfacePoint p = average({point(c[0]), point(c[1]), point(c[2])});
  int v = mesh.split_face(f);
  if (v != num_input_vertices + static_cast<int>(constructed.size()))
    throw Error(ErrorKind::Internal, "refined surface out of step with its mesh", {v});
  constructed.push_back(std::move(p));
  return v;
}

}  // namespace igm
