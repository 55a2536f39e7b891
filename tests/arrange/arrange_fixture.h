#pragma once
// Shared by tests/arrange: synthetic convex 4g-gons, their disks and a layout overlaid on them.
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/arrange/synthetic_disk.h"
#include "igm/embed/polygon.h"
#include "igm/igm/patch_maps.h"
#include "igm/layout/quad_layout.h"

namespace igm_test {

inline std::vector<igm::Point2q> schema_polygon(int g) {
  using igm::Rational;
  if (g == 1) return {{Rational(0), Rational(0)}, {Rational(1), Rational(0)}, {Rational(1), Rational(1)}, {Rational(0), Rational(1)}};
  return igm::rational_circle_polygon(4 * g);
}

inline igm::Point2q schema_centre(int g) {
  using igm::Rational;
  return g == 1 ? igm::Point2q{Rational(1, 2), Rational(1, 2)} : igm::Point2q{Rational(0), Rational(0)};
}

struct Pipeline {
  igm::PlanarTriangulation disk;
  igm::QuadLayout layout;
  std::vector<igm::Segment2> geometry;  // every layout edge, then the quads' diagonals
  igm::OverlayResult overlay;
};

/// The paper's layout (a1 b1 a1^-1 b1^-1 ... pairing) with its diagonals, overlaid on a synthetic disk.
inline Pipeline run_overlay(int g, const igm::SyntheticDiskOptions& o) {
  Pipeline p;
  const auto corners = schema_polygon(g);
  p.disk = igm::make_synthetic_disk(corners, schema_centre(g), o);
  const std::vector<int> mates = igm::canonical_side_mates(g);
  igm::LayoutOptions lo;
  lo.kind = igm::LayoutKind::Paper;
  p.layout = igm::make_layout(corners, schema_centre(g), mates, lo);
  for (const igm::LayoutEdge& e : p.layout.edges) p.geometry.push_back({p.layout.points[e.a], p.layout.points[e.b]});
  const std::vector<int> d = igm::quad_diagonals(p.layout);
  for (std::size_t q = 0; q < d.size(); ++q)
    if (d[q] >= 0) p.geometry.push_back({p.layout.points[p.layout.quads[q][d[q]]], p.layout.points[p.layout.quads[q][d[q] + 2]]});
  p.overlay = igm::overlay_segments(p.disk, p.geometry);
  return p;
}

}  // namespace igm_test
