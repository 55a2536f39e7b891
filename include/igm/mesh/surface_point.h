#pragma once
// Exact points of an input triangle surface, and a refined mesh whose constructed vertices are
// such points. A SurfacePoint is a convex combination of at most three input vertices that are
// the corners (or an edge, or a vertex) of ONE input face, with exact rational weights.
#include <array>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/exact/rational.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct SurfacePoint {
  std::array<int, 3> v{-1, -1, -1};  // input vertex ids, the used ones first (ascending), unused = -1
  std::array<Rational, 3> w;         // weights of v, > 0 on used slots (combine() drops zero terms); unused = 0

  SurfacePoint() = default;
  SurfacePoint(const SurfacePoint&) = default;
  SurfacePoint& operator=(const SurfacePoint&) = default;
  /// Moves by swapping the weights (mpq_class's own move constructor is not noexcept, so a growing
  /// std::vector<SurfacePoint> would copy every point instead). `o` is left valid, its value
  /// unspecified. GMP aborts, never throws, when it runs out of memory.
  SurfacePoint(SurfacePoint&& o) noexcept : v(o.v) {
    for (int i = 0; i < 3; ++i) mpq_swap(w[i].get_mpq_t(), o.w[i].get_mpq_t());
  }
  SurfacePoint& operator=(SurfacePoint&& o) noexcept {
    v = o.v;
    for (int i = 0; i < 3; ++i) mpq_swap(w[i].get_mpq_t(), o.w[i].get_mpq_t());
    return *this;
  }

  /// The input vertex `id` itself (weight 1).
  static SurfacePoint vertex(int id);
  /// Number of used slots (1..3).
  int size() const;
};

/// a * ta + b * tb, exactly. Pre: ta, tb >= 0, ta + tb = 1 (not checked), and the supports of a and
/// b together hold at most three vertices (else igm::Error(Internal)). O(1) GMP operations.
SurfacePoint combine(const SurfacePoint& a, const Rational& ta, const SurfacePoint& b, const Rational& tb);

/// The same into r (its weights' limbs reused; r must be neither a nor b), for callers that make many.
void combine_into(SurfacePoint& r, const SurfacePoint& a, const Rational& ta, const SurfacePoint& b,
                  const Rational& tb);
/// (1 - t) a + t b, exactly (t in [0, 1]).
SurfacePoint lerp(const SurfacePoint& a, const SurfacePoint& b, const Rational& t);
/// The same into r (r must be neither a nor b).
void lerp_into(SurfacePoint& r, const SurfacePoint& a, const SurfacePoint& b, const Rational& t);

/// The unweighted average of the points (exact). Pre: non-empty, joint support <= 3 vertices.
SurfacePoint average(const std::vector<SurfacePoint>& points);

/// The exact point wa*a + wb*b + wc*c (weights >= 0 summing to 1, not checked), where a, b, c are
/// the corners of one refined face (so their joint support is one input face). O(1) GMP operations.
SurfacePoint barycentric_point(const SurfacePoint& a, const SurfacePoint& b, const SurfacePoint& c,
                               const std::array<Rational, 3>& w);

/// The 3D position: the exact point sum w_i input_positions[v_i], each coordinate rounded toward
/// zero (to_double); a one-vertex point gives the input position itself. For output and display
/// only, never for decisions. O(1) GMP operations.
Vec3d evaluate(const SurfacePoint& p, const std::vector<Vec3d>& input_positions);

/// A refinement of an input surface: `mesh` has the input vertices 0..num_input_vertices-1 at their
/// input positions and constructed vertices num_input_vertices.. whose exact location is
/// constructed[v - num_input_vertices]. Every face of `mesh` lies inside one input face. Later
/// stages may append more constructed vertices (keep `constructed` in step with the mesh).
struct RefinedSurface {
  TriMesh mesh;
  int num_input_vertices = 0;
  std::vector<SurfacePoint> constructed;
  std::vector<Vec3d> input_positions;

  bool is_input_vertex(int v) const { return v < num_input_vertices; }
  /// Exact location of vertex v (input vertices give a weight-1 point). O(1).
  SurfacePoint point(int v) const {
    return v < num_input_vertices ? SurfacePoint::vertex(v) : constructed[v - num_input_vertices];
  }
  /// Double 3D position of vertex v.
  Vec3d position(int v) const {
    return v < num_input_vertices ? input_positions[v] : evaluate(constructed[v - num_input_vertices], input_positions);
  }
  /// Splits the edge of half-edge h at (1 - t) origin + t target, exactly; returns the new vertex.
  int split_edge(int h, const Rational& t);
  /// Splits face f at the exact barycentre of its corners; returns the new vertex.
  int split_face(int f);
};

}  // namespace igm
