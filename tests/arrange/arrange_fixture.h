#pragma once
// Shared by tests/arrange, tests/igm, tests/extract: synthetic convex 4g-gons and their disks.
#include <vector>

#include "igm/arrange/overlay.h"
#include "igm/arrange/quad_template.h"
#include "igm/arrange/synthetic_disk.h"

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
  igm::QuadTemplate tmpl;
  std::vector<igm::TemplateSegment> segments;
  std::vector<igm::Segment2> geometry;
  igm::OverlayResult overlay;
};

inline Pipeline run_overlay(int g, const igm::SyntheticDiskOptions& o) {
  Pipeline p;
  const auto corners = schema_polygon(g);
  p.disk = igm::make_synthetic_disk(corners, schema_centre(g), o);
  p.tmpl = igm::make_quad_template(corners, schema_centre(g));
  p.segments = igm::template_segments(p.tmpl);
  p.geometry = igm::template_geometry(p.tmpl, p.segments);
  p.overlay = igm::overlay_segments(p.disk, p.geometry);
  return p;
}

}  // namespace igm_test
