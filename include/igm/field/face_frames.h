#pragma once
// Per-face tangent frames of a triangle surface and the Levi-Civita transport between
// neighbouring faces: the common ground of the cross field (cross_field.h), its curvature guide
// (curvature.h) and the tracing of its separatrices.
//
// Frame of face f: its reference half-edge r = reference[f]; angles in the frame are measured
// counter-clockwise (the face's orientation) from the direction of r. The frame is intrinsic:
// with A and B the corner angles of f at origin(r) and target(r) (each in [0, pi], from the 3D
// positions), the direction of r has angle 0, that of next(r) pi - B, that of prev(r) pi + A
// (edge_angle). In 3D the frame is axis_x = unit(p(target r) - p(origin r)),
// axis_y = normal x axis_x, so that the direction of angle phi is cos(phi) x + sin(phi) y (equal
// to the intrinsic angles up to rounding on a non-degenerate face).
//
// Transport across the interior edge of half-edge h (face f = face(h), g = face(twin(h))): unfold
// g onto the plane of f across the shared edge; the direction of angle phi in f's frame is then
// the direction of angle phi + rho_h in g's frame, where rho_h = a(twin h) + pi - a(h) + 2 pi w_h
// is taken in (-pi, pi] by the integer w_h (a: edge_angle). rho_twin = -rho_h exactly and
// w_twin = -w_h - 1. The integers w_h are what makes the field's singularity indices exact
// integers (cross_field.h): nothing about them is decided by a tolerance.
//
// Reference half-edge (deterministic): a face with a constrained edge of non-zero length (a
// boundary edge, or a half-edge flagged in `constrained`: the feature edges of issue 45) takes
// its longest constrained half-edge (ties: the first of 3f, 3f+1, 3f+2); any other face takes 3f
// (x = unit(p1 - p0)) unless p1 == p0, in which case its longest half-edge (ties as above).
// Degenerate faces (fallbacks, documented at face_frames): a zero normal (collinear or
// coincident corners) is replaced by the sum of the edge-neighbours' area vectors, and if that is
// zero or parallel to axis_x, by a fixed unit vector orthogonal to axis_x; a zero axis_x (all
// three corners coincide) by (1, 0, 0). Corner angles of zero-length edges are 0. The intrinsic
// angles stay well defined, so every index stays an integer and Poincare-Hopf holds exactly.
#include <vector>

#include "igm/exact/predicates.h"
#include "igm/mesh/trimesh.h"

namespace igm {

struct FaceFrames {
  std::vector<int> reference;         // per face: its reference half-edge r (a half-edge of f)
  std::vector<double> edge_angle;     // per half-edge h: angle of h's direction in face(h)'s frame
  std::vector<double> transport;      // per half-edge: rho_h in (-pi, pi]; 0 for a boundary half-edge
  std::vector<int> transport_turns;   // per half-edge: w_h (see the top of the file); 0 for boundary
  std::vector<double> area;           // per face: 3D area (0 for a degenerate face)
  std::vector<Vec3d> axis_x, axis_y;  // per face: the 3D frame (unit, orthogonal)
  std::vector<Vec3d> normal;          // per face: axis_x x axis_y
  int degenerate_faces = 0;           // faces whose normal or axis_x took a fallback
};

/// Frames and transport of every face of a connected surface (closed, or with boundary: twin -1
/// on boundary half-edges). Pre: positions.size() == mesh.num_vertices() and finite (the caller,
/// compute_cross_field, checks); `constrained` empty or one flag per half-edge. Deterministic;
/// cost O(F).
FaceFrames face_frames(const TriMesh& mesh, const std::vector<Vec3d>& positions,
                       const std::vector<char>& constrained = {});

/// The 3D unit direction of angle phi in face f's frame.
Vec3d frame_direction(const FaceFrames& frames, int f, double phi);

}  // namespace igm
