#pragma once
// The quad template of the polygonal schema (paper §4.2, Fig. 3-4): per group of four sides
// l_i l_j l_i^-1 l_j^-1, three inner points and five quads sharing the polygon centre.
#include <array>
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/exact/predicates.h"

namespace igm {

/// Planar template. Point indices: 0..4g-1 are the polygon corners (corner k = P_k, all copies
/// of the root), 4g is the centre C, 4g+1+3i+j (j = 0,1,2) is inner point A_j of group i.
/// For g = 1 there are only the 4 corners and one quad, the polygon itself.
struct QuadTemplate {
  int genus = 0;
  std::vector<Point2q> points;
  /// Per point: its layout vertex after gluing the polygon's sides: 0 = root (every corner),
  /// 1 = centre, 2+3i+j = A_j of group i. num_layout_vertices() = 2+3g (1 for g = 1).
  std::vector<int> layout_vertex;
  /// Strictly convex, counter-clockwise quads (Q0 Q1 Q2 Q3) -> (0,0),(1,0),(1,1),(0,1).
  /// Group i owns quads 5i..5i+4: (P0 P1 A0 C), (P1 P2 A1 A0), (P2 P3 A2 A1), (P3 P4 C A2), (A0 A1 A2 C).
  std::vector<std::array<int, 4>> quads;
  /// Per quad: 0 = diagonal Q0-Q2, 1 = diagonal Q1-Q3 (the shorter one, exactly), -1 = none:
  /// the quad is a parallelogram, its map to the unit square is affine and needs no diagonal.
  std::vector<int> diagonal;
  /// Per polygon side s (corner s -> corner s+1): the quad containing it and the edge index e
  /// of that quad (edge e runs from Q_e to Q_(e+1)); the side runs in the quad edge's direction.
  std::vector<std::array<int, 2>> side_quad;

  int num_layout_vertices() const { return genus == 1 ? 1 : 2 + 3 * genus; }
  int num_corners() const { return 4 * genus; }
};

/// Builds the template on a strictly convex counter-clockwise polygon with 4g corners (g >= 1)
/// and a centre strictly inside. Inner points of group i with corners P0..P4 (P4 = next group's
/// P0): A0 = (P1+P2+C)/3, A1 = C + 5/6 (P2-C), A2 = (P2+P3+C)/3. (A1 = (C+P2)/2 would make
/// quad (A0 A1 A2 C) reflex for large g: in the thin-wedge limit it needs 2/3 < lambda < 1.)
/// Every quad is checked strictly convex with exact orient2d.
/// Errors: InvalidArgument for a corner count not a positive multiple of 4, a polygon that is
/// not strictly convex and counter-clockwise, a centre not strictly inside; Internal if a quad of
/// the template is not strictly convex (never proceeds with a bad template). Cost O(g).
QuadTemplate make_quad_template(const std::vector<Point2q>& corners, const Point2q& centre);

/// One region of the template's triangulation: a triangle of a quad cut by its diagonal, or the
/// whole quad (diagonal -1). `uv` are the images of `corners` in the unit square; the region's
/// map to the unit square is the affine map sending corners[0..2] to uv[0..2].
struct TemplateRegion {
  int quad = -1;
  std::vector<int> corners;     // template point indices, ccw (3, or 4 for a parallelogram)
  std::vector<Point2q> uv;      // unit-square images, same order
};

/// A segment of the template (quad edge or diagonal), from point a to point b; `left`/`right`
/// are the regions on either side (-1 outside the polygon).
struct TemplateSegment {
  int a = -1, b = -1;
  int left = -1, right = -1;
  bool diagonal = false;
};

std::vector<TemplateRegion> template_regions(const QuadTemplate& t);
/// Every quad edge once plus every diagonal; order is deterministic. Cost O(g log g).
std::vector<TemplateSegment> template_segments(const QuadTemplate& t);
/// The segments as geometry, in the same order, for overlay_segments.
std::vector<Segment2> template_geometry(const QuadTemplate& t, const std::vector<TemplateSegment>& segments);

/// Test and benchmark helper: n corners on the unit circle, exactly rational
/// ((1-s^2)/(1+s^2), 2s/(1+s^2)) with s a dyadic approximation (`bits` fractional bits) of
/// tan(theta_k/2), theta_k = 2 pi (k + 1/2) / n; counter-clockwise, strictly convex (checked).
std::vector<Point2q> rational_circle_polygon(int n, int bits = 24);

}  // namespace igm
