#pragma once
// Internal to the field layout (motorcycle.cpp, field_layout.cpp): the per-face frames of a cross
// field given by one direction per face, its nearest matchings, and the separatrix rays of a vertex.
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/field/motorcycle.h"
#include "igm/mesh/trimesh.h"

namespace igm::field_detail {

/// v rotated by k quarter turns counter-clockwise.
Vec2d rot90(const Vec2d& v, int k);

/// A separatrix ray of a vertex v: inside face `face` along field direction `dir` of that face
/// (edge == -1); or along the mesh edge `edge` (a half-edge leaving v; the field direction `dir`
/// of face(edge) points along it); edge == -2 marks the boundary edge behind v on an open fan.
struct VertexRay {
  int face = -1, dir = 0, edge = -1;
};

/// A vertex's rays in counter-clockwise order. Interior: `valence` rays a quarter turn apart in
/// the field. Boundary: rays[0] along the boundary edge leaving v, then the valence - 1 interior
/// rays, then the boundary edge arriving at v (valence = the boundary angle in quarter turns).
/// valence -1 (no rays): a degenerate face around v, or crossings that do not cancel.
struct VertexRays {
  std::vector<VertexRay> rays;
  int valence = -1;
  bool boundary = false;
};

/// Per face: corners in a local orthonormal frame (corner 0 at the origin, corner 1 on +x, corner 2
/// above), the field's unit direction in it; per half-edge h of an interior edge the matching:
/// direction j of face(h) is direction (j + shift[h]) % 4 of face(twin(h)).
struct FieldFrames {
  const TriMesh& mesh;
  std::vector<std::array<Vec2d, 3>> corner;
  std::vector<Vec2d> dir;
  std::vector<char> good;  // the face has positive area and a direction with a tangent component
  std::vector<int> shift;
  /// Per face: corner 0 and the frame's axes in 3D (to carry points and directions across).
  std::vector<Vec3d> origin, axis_x, axis_y;

  FieldFrames(const TriMesh& mesh, const std::vector<Vec3d>& positions, const std::vector<Vec3d>& face_direction);
  /// Field direction j of face f (unit, in f's frame).
  Vec2d direction(int f, int j) const;
  /// Half-edge h as a vector in its face's frame.
  Vec2d edge_vector(int h) const;
  /// The direction index of face f nearest to v (ties: the lower index).
  int nearest_direction(int f, const Vec2d& v) const;
  /// The separatrix rays of vertex v (VertexRays). Cost O(valence).
  VertexRays vertex_rays(int v) const;
};

/// What trace_motorcycles_reusing carries from one call to the next on the same mesh, positions,
/// field and options but for the seeds and banned rays (build_field_layout's rounds): the vertices'
/// rays, and each start ray's solo pre-pass result (kept while the set of traced vertices, which
/// alone decides it, stays the same). The graph is the same with or without it.
struct TraceReuse {
  struct Solo {
    bool reached = false;
    int vertex = -1, ray = -1, steps = 0;
    int steers = 0;  // the steering it counted (TraceStats::steers)
  };
  std::vector<VertexRays> rays;
  std::vector<char> rays_done;
  std::vector<char> solo_traced;  // the traced vertices the solo results below were made with
  std::vector<std::vector<std::pair<int, Solo>>> solo;  // per vertex: (ray, result)
};

/// trace_motorcycles (field/motorcycle.h) with the frames given (those of the positions scaled by
/// unit_scale, as trace_motorcycles makes them) and what earlier calls left in `reuse`.
TraceGraph trace_motorcycles_reusing(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                                     const std::vector<Vec3d>& face_direction, const TraceOptions& options,
                                     const FieldFrames& frames, TraceReuse& reuse);

/// Trace point q (field/motorcycle.h) in the barycentric plane (w1, w2) of face f, exactly, or
/// nothing when q is not in f's closure (a corner, a point of one of its edges, or a point of f).
std::optional<Point2q> point_in_face_if(const TriMesh& mesh, const TracePoint& q, int f);
/// The same where q must lie in f's closure: else igm::Error(Internal).
Point2q point_in_face(const TriMesh& mesh, const TracePoint& q, int f);

}  // namespace igm::field_detail
