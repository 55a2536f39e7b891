#pragma once
// Quality metrics of igm's outputs: the distortion of an IGM (the per-corner UV map of a triangle
// mesh) and the shape of a quad mesh, with its two-sided distance to the input surface. Every
// metric is defined in docs/quality.md precisely enough to recompute by hand; the comments below
// are short reminders. Measurements in double: nothing certified depends on them (the validity of
// an output is the certifier's, certify/README.md).
#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "igm/exact/predicates.h"

namespace igm {

/// Area-weighted (IGM) or plain (quad) quantiles of one metric (docs/quality.md, "Quantiles").
struct Quantiles {
  double median = 0, p90 = 0, p99 = 0, max = 0;
};

/// The distortion of an IGM, per triangle of the map 3D -> UV (docs/quality.md, "IGM").
struct IgmQuality {
  int triangles = 0;
  int degenerate = 0;   // zero 3D area or non-positive UV area (exact tests): excluded, counted
  Quantiles conformal;  // s1/s2 >= 1 of the map 3D -> UV per triangle, weighted by 3D area
  Quantiles area;  // max(r, 1/r), r = (A_uv / sum A_uv) / (A_3d / sum A_3d), weighted by 3D area
  double symmetric_dirichlet = 0;  // 3D-area-weighted mean of s1^2+s2^2+s1^-2+s2^-2 after scaling
                                   // all UVs by sqrt(sum A_3d / sum A_uv); 4 = isometry
};

/// Measures an IGM: triangle t has corners positions[triangles[t][i]] in 3D and corner_uv[t][i]
/// in the plane (i = 0, 1, 2). Each triangle is mapped isometrically into the plane; J, the 2x2
/// Jacobian of the affine map from there to its UV triangle, has singular values s1 >= s2. A
/// triangle is degenerate when its 3D area is zero or its UV orientation is not positive (both
/// decided exactly, igm::orient2d), or when a metric is not finite in double (only for triangles
/// ~1e-150 times the size of the mesh); degenerate triangles are counted and left out of every
/// sum. No triangle left: every metric 0. Invariant under a uniform scaling of the 3D positions
/// and, apart, of the UVs.
/// Pre (checked): corner_uv.size() == triangles.size() (igm::Error(InvalidArgument)), vertex ids
/// in range (igm::Error(IndexOutOfRange) naming the triangle), finite coordinates of the vertices
/// and UVs used (igm::Error(NonFinite) naming the vertex or triangle). Cost O(T log T) (sorting
/// for the quantiles).
IgmQuality measure_igm(const std::vector<Vec3d>& positions,
                       const std::vector<std::array<int, 3>>& triangles,
                       const std::vector<std::array<Vec2d, 3>>& corner_uv);

struct QuadQualityOptions {
  bool distance = true;  // compute the two-sided distance (the costly part)
  /// Bound on the samples per side of the two-sided distance: a side with more samples is
  /// subsampled at a fixed stride (docs/quality.md). 200,000 measures a 1M-triangle input against
  /// a 20k-quad mesh in about 0.8 s of CPU time on the 2-core test machine (igm_bench_quality),
  /// of which 0.3 s build the input's hierarchy. Must be >= 1.
  std::size_t max_samples = 200000;
};

/// The shape of a quad mesh and its distance to the input surface (docs/quality.md, "Quad mesh").
struct QuadQuality {
  int quads = 0, vertices = 0;
  int degenerate = 0;          // quads with a zero edge or a zero normal: their SJ counts as 0
  std::map<int, int> valence;  // quads around a vertex -> number of such vertices (0: unused)
  /// Interior vertices (on no edge of a single quad) whose valence is not 4, and the largest
  /// valence of an interior vertex (0 without one).
  int irregular_vertices = 0, max_valence = 0;
  double sj_min = 0, sj_p5 = 0, sj_median = 0;  // scaled Jacobian (SJ)
  double sj_below_half = 0;                     // fraction of quads with SJ < 0.5
  double sj_nonpositive = 0;                    // fraction of quads with SJ <= 0
  // |corner angle - 90| in degrees, over corners
  double angle_deviation_median = 0, angle_deviation_p95 = 0;
  double area_p95_over_p5 = 0;  // quad area quantiles ratio (+inf if p5 is 0)
  double area_ratio = 0;        // total quad area / total input area
  // fraction of the total quad area covered by the smallest half (floor(quads / 2)) of the quads
  double smallest_half_area = 0;
  bool distance_measured = false;  // options.distance
  // two-sided quad mesh <-> input, / input bbox diagonal (+inf if a side is empty)
  double distance_max = 0, distance_p99 = 0;
  // samples measured on each side (after subsampling)
  std::size_t distance_samples_quads = 0, distance_samples_input = 0;
};

/// Measures a quad mesh (each quad p0..p3 counter-clockwise seen from outside) against the
/// triangle surface it remeshes. Quantities that divide by zero (no quads, zero input area or
/// diagonal) are left non-finite (null in JSON); with no quads the other metrics are 0.
/// Pre (checked): ids in range (igm::Error(IndexOutOfRange) naming the quad or triangle), every
/// position of both meshes finite (igm::Error(NonFinite) naming the vertex), options.max_samples
/// >= 1 (igm::Error(InvalidArgument)). Invariant under a uniform scaling of both meshes together
/// (the coordinates are first scaled by a power of two, exactly, to magnitudes below 1).
/// Cost O(Q log Q + T) without the distance; with it, two hierarchies (O(Q log Q + T log T)) and
/// at most 2 * options.max_samples nearest-point queries (timing at QuadQualityOptions).
QuadQuality measure_quads(const std::vector<Vec3d>& quad_positions,
                          const std::vector<std::array<int, 4>>& quads,
                          const std::vector<Vec3d>& input_positions,
                          const std::vector<std::array<int, 3>>& input_triangles,
                          const QuadQualityOptions& options = {});

/// How the feature metrics sample (docs/quality.md, "Features").
struct FeatureQualityOptions {
  double tolerance = 0.002;  // a sample is covered within this fraction of the input's diagonal
  double spacing = 0.0005;   // samples at most this fraction of the diagonal apart along each edge
  /// Bound on the samples: past it the spacing grows to total feature length / max_samples.
  /// Must be >= 1.
  std::size_t max_samples = 2000000;
};

/// How well a quad mesh follows the input's feature curves (features/feature_edges.h;
/// docs/quality.md, "Features"). A report (geometric, in doubles); the exact statement that the
/// field layout's feature edges lie on isolines is the certifier's (certify::Report::features).
struct FeatureQuality {
  int edges = 0;              // feature edges measured
  int curves = 0, corners = 0;  // as detected (filled by the caller: the pipeline copies them)
  /// Of the edges, those in chains too short for the quads to follow (FeatureStats::short_edges,
  /// the resolution rule: measured here, not followed by the field layout; filled by the caller).
  int short_edges = 0;
  double length = 0;          // their total 3D length, in the input's units
  /// Fraction of the feature length within tolerance x diagonal of a quad edge; null (nan) with
  /// no feature length, 0 with no quads.
  double covered_fraction = 0;
  /// Length-weighted max and p99 of the samples' distance to the nearest quad edge, / diagonal
  /// (fractions, as QuadQuality's distances; +inf with no quads, nan with no feature).
  double distance_max = 0, distance_p99 = 0;
  std::size_t samples = 0;
};

/// Samples every feature edge (a, b) (ids into input_positions) at the midpoints of
/// n = ceil(length / step) equal pieces (step = options.spacing x diagonal, or more under
/// max_samples), each weighing length / n, and measures each sample's distance to the nearest
/// edge segment of the quads (a uniform grid over the quad edges searched in growing shells: exact
/// nearest in double, deterministic for any thread count). diagonal: of the bounding box of all
/// input_positions. Pre (checked): ids in range (igm::Error(IndexOutOfRange)), finite positions
/// (NonFinite), options in range: 0 < spacing, 0 <= tolerance, max_samples >= 1
/// (InvalidArgument). Invariant under a uniform scaling of both meshes. Cost O(S x the segments
/// near each sample + E_q log E_q) for S samples and E_q quad edges.
FeatureQuality measure_features(const std::vector<Vec3d>& input_positions,
                                const std::vector<std::array<int, 2>>& feature_edges,
                                const std::vector<Vec3d>& quad_positions,
                                const std::vector<std::array<int, 4>>& quads,
                                const FeatureQualityOptions& options = {});

/// Weighted quantiles (docs/quality.md, "Quantiles"): for each q in `qs`, the smallest value v such
/// that the total weight of the values <= v is >= q times the total weight (sums in double, in
/// increasing order of value). Empty input: 0 for every q. Pre (checked, igm::Error
/// (InvalidArgument)): values.size() == weights.size(), no nan value (+-inf are ordered as
/// usual), finite weights >= 0. O(n log n).
std::vector<double> weighted_quantiles(const std::vector<double>& values,
                                       const std::vector<double>& weights,
                                       const std::vector<double>& qs);

/// The same with unit weights: the ceil(q n)-th smallest value (the smallest for q n <= 1).
std::vector<double> quantiles(const std::vector<double>& values, const std::vector<double>& qs);

/// JSON objects: the members above in their order, keys their names (deterministic), numbers in
/// the shortest form that reads back to the same double, null for inf and nan (and for the
/// distances when not measured); `valence` an object from the valence (as a string) to the count.
std::string to_json(const IgmQuality& q);
std::string to_json(const QuadQuality& q);
/// {"edges", "curves", "corners", "length", "covered_fraction", "distance_max", "distance_p99",
/// "samples"} (null for nan and inf).
std::string to_json(const FeatureQuality& q);
/// For the quality line, e.g. "features 12 curves, 24 edges: 87.5 % covered, distance max 1.2 %
/// p99 0.9 %" ("no features" without any).
std::string summary_line(const FeatureQuality& q);

/// One line for a human, e.g. "quads 10234: SJ median 0.93 p5 0.61 min -0.20, <0.5 3.1 %, <=0
/// 0.4 %, angle dev median 6.1 deg, area/input 0.998, smallest half 41 %, distance max 0.3 %;
/// IGM conformal p99 2.7, area p99 3.1" (distance as a percentage of the input's diagonal).
std::string summary_line(const IgmQuality& igm, const QuadQuality& quads);

}  // namespace igm
