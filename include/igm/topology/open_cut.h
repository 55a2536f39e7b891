#pragma once
// Topology stage for OPEN surfaces (genus g, b >= 1 boundary loops): the surface cut into a disk
// whose boundary has glued pairs of sides (each twice, in opposite directions) and FREE sides
// (pieces of the boundary loops, glued to nothing). Closed components go to cut_to_canonical_disk
// (g >= 1) or cut_sphere (g = 0). The steps:
//  1. filling: every boundary loop j gets a fan to a new vertex h_j (at the loop's centroid): the
//     filled surface S' is closed, of genus g. Its input vertices are S's, then h_0 .. h_{b-1};
//     the fan triangles are never part of the disk. A loop of fewer than 4 vertices on a disk
//     (g = 0, b = 1) first gets boundary edges split at their midpoints (4 corners need 4 vertices).
//  2. chords: every interior edge of S joining two boundary vertices is split at its midpoint.
//     Then no face touches two loops, each filled hole (fan plus loop) is a full subcomplex of S',
//     and the interior vertices of S span a connected subcomplex I homotopy equivalent to S.
//  3. loops (g >= 1): cut_to_canonical_disk on S' without the normal form or the congestion
//     reweighting, at a root in I (OpenCutOptions::root, or the interior vertex of largest valence,
//     lowest id), with a metric that puts every boundary vertex and every h_j farther than 4x the
//     total length of I's edges from everything (positions used only for the metric). Then every
//     tree path and every band of the greedy basis lies in I: a path through the holes is longer
//     than any path in I, and the edges touching a hole are heavier than all others in the
//     cotree's maximum spanning tree and form no dual cycle (such a cycle would lie in the star of
//     one filled hole, a disk, so it would separate the vertices, and the tree crosses every such
//     cut), so they all go into the cotree. The detached strands cross only edges at vertices of I:
//     every loop vertex is interior to S, no exact point involves an h_j. The loops are then
//     tightened (tighten_loops) with the boundary vertices and the h_j barred. Checked: a loop
//     vertex on a boundary or a fan is igm::Error(Internal).
//  4. legs: the holes are joined to the cut one at a time, each by a leg from a CORNER of the
//     current disk (a root copy, or a hole vertex where an earlier leg ended; for g = 0 the first
//     leg starts anywhere on loop 0) to a vertex of the hole, through the interior of the current
//     region only. Cutting it keeps a disk and inserts the sides c d c^-1 at its start corner (c
//     the leg, d the whole loop, a free side from the leg's end back to it). The searches (3D
//     lengths) run on the passable vertices (not on a loop, a leg or a boundary) and the chords
//     (interior edges between two blocked vertices), a chord crossed at its midpoint, split off
//     when a leg uses it (it costs one mean edge length more): then every hole is reachable from
//     every corner, however the cuts box a corner or a pocket in, and every leg has an interior
//     vertex. Order: the minimum spanning tree of the holes and the root over one multi-source
//     search from all of them (Voronoi regions touching across an edge), depth-first from the
//     root; each leg runs from its parent's corners to its hole, a search that settles about the
//     ball between them. Where that finds nothing, a search from every corner to the nearest hole
//     not joined. At most b rounds of two searches.
//     This differs from a path h_1 -> h_2 -> ... through the fans (each inner loop split in two):
//     a leg touches its hole at one vertex, so each hole adds 3 sides instead of 4; for genus 0
//     and b >= 2 the word has 3b - 2 sides (the annulus: loop 0, leg, loop 1, leg^-1), for
//     g >= 1 4g + 3b (the 4g loop sides, and at corners c_j d_j c_j^-1).
//  5. corners: g = 0, b = 1: four loop vertices, the first of the loop and those nearest a quarter,
//     a half and three quarters of its 3D length (by index where the length is 0), each after the
//     last. An odd side count gets one more corner: the vertex nearest the middle (by arc length)
//     of the longest free side, so the count is even and >= 4.
//  6. embedding pre-conditions (embed/tutte.h): every interior disk edge joining two vertices of
//     one side (a corner lies on its two sides) is split at its midpoint (one pass, as in
//     cut_to_canonical_disk's step 4); then no triangle has three vertices on one side.
//  7. the disk: the faces of S only (S' renumbered so that they come first), cut along the loops
//     and legs; its boundary is one ccw cycle of sides from corner to corner.
// Every constructed vertex is an exact point of one input face (SurfacePoint); the points of the
// closed cut (made on S' with the chord midpoints as input vertices) are composed back onto S'.
#include <array>
#include <string>
#include <vector>

#include "igm/mesh/surface_point.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/tighten_loops.h"

namespace igm {

struct OpenCutOptions {
  /// g >= 1: the root, a vertex of S not on a boundary loop; -1: the interior vertex of S of
  /// largest valence (lowest id), or with none a chord midpoint of step 2. Ignored for g = 0.
  int root = -1;
  /// Tighten the loops (step 3, tighten_loops with the holes barred): fewer vertices.
  bool tighten = true;
  /// Passed to the closed cut (CutOptions::parallel): the same result either way.
  bool parallel = true;
};

struct OpenCutStats {
  int genus = 0, boundary_loops = 0;
  int vertices_before = 0, faces_before = 0;  // S
  int vertices_after = 0, faces_after = 0;    // the refined S' (fans included)
  int disk_vertices = 0, disk_faces = 0;
  int boundary_splits = 0;      // loop edges split so that a disk's loop has 4 vertices (step 1)
  int chord_splits = 0;         // step 2
  int leg_chord_splits = 0;     // chords the legs cross, split at their midpoints (step 4)
  int precondition_splits = 0;  // step 6
  int legs = 0, leg_edges = 0;  // step 4
  int extra_corners = 0;        // corners added to make the side count even (step 5)
  CutStats closed;              // the closed cut's (step 3; g >= 1)
  TightenStats tightening;      // step 3's tightening
  double seconds_loops = 0, seconds_legs = 0, seconds_total = 0;
};

/// One side of the disk boundary.
struct OpenSide {
  std::vector<int> disk_vertices;  // from the corner where it starts to the next one, ccw (interior on the left)
  int mate = -1;                   // the glued side (traversed the other way), or -1: a free side
  int loop = -1;                   // free side: the boundary loop it lies on (index into boundary_loops)
};

struct OpenCut {
  RefinedSurface surface;  // the refined FILLED surface S' (closed TriMesh)
  int num_surface_faces = 0;  // its faces 0..num_surface_faces-1 are S's (refined); the fans come after
  int genus = 0, boundary_loops = 0;
  /// Disk vertex ids, ccw; disk triangle f is surface face f (f < num_surface_faces; no fan triangle).
  std::vector<std::array<int, 3>> disk_triangles;
  std::vector<int> disk_to_surface;  // disk vertex -> surface vertex (of S')
  std::vector<int> boundary;         // the disk's boundary cycle, ccw, from a corner
  std::vector<OpenSide> sides;       // consecutive along `boundary`, covering it; sides[0] starts at boundary[0]
  int root = -1;                     // g >= 1: the root's surface vertex; else -1
  /// Each loop of the input refined: surface vertices in the direction of the boundary half-edges,
  /// from the loop's first input vertex.
  std::vector<std::vector<int>> refined_loops;
  OpenCutStats stats;
};

/// Cuts an open surface into a disk with glued and free sides (steps above). Pre: `surface` as
/// validate_surfaces makes it (connected, manifold, oriented, every vertex used, loops in the
/// direction of the boundary half-edges). Throws igm::Error(Unsupported) for a closed surface
/// (b = 0: use cut_to_canonical_disk or cut_sphere); igm::Error(InvalidArgument) for bad input
/// (positions, loops that are not the boundary, a genus that does not match, a root on a boundary
/// or out of range), NonFinite for a non-finite coordinate, the errors of TriMesh::from_triangles
/// for non-manifold triangles; igm::Error(Internal) if an invariant breaks. Post: check_open_cut
/// returns "". Cost: the closed cut's (without the normal form, one root, g >= 1) plus
/// O(n log n) for the legs' order and O(sum over the legs of the nodes their searches settle x
/// log), O(n) splits and O(n) for the disk.
OpenCut cut_open_surface(const SurfaceComponent& surface, const OpenCutOptions& options = {});

/// The post-conditions of cut_open_surface, recomputed from the arrays: "" or the first violation.
/// The refined S' is a valid closed TriMesh whose input vertices keep their positions; every
/// constructed point is canonical and lies in one input face (2 vertices: an input edge, 3: an
/// input face); faces below num_surface_faces lie in S's faces (no vertex involves an h_j), the
/// others in the fans; the disk triangles are those faces' corners' copies and form a
/// topological disk (each vertex one fan, Euler characteristic 1) whose one boundary cycle is
/// `boundary`, in its direction; the sides cover it consecutively, >= 4 and even in number; glued
/// sides are mates with the same surface vertices in opposite orders; the free sides' edges are
/// exactly the refined loops' edges, each once, in their direction and on their loop; no interior
/// disk edge joins two vertices of one side and no triangle has three; no h_j in the disk. O(n log n).
std::string check_open_cut(const SurfaceComponent& surface, const OpenCut& cut);

}  // namespace igm
