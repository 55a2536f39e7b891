// layout_grid (the combinatorics of a sized layout's quads) and, on it, the floor of the sizing:
// minimum_chord_counts is swept on every layout the pipeline builds (closed genus 1-4: spread with
// every row count, kite, paper; open surfaces from the open cut of generated meshes: disk, annulus,
// genus 0 with 3-4 loops, genus 1-2 with loops), certified by the certifier's quad check.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <random>
#include <string>

#include "certify/certify.h"
#include "igm/core/error.h"
#include "igm/embed/polygon.h"
#include "igm/layout/layout_grid.h"
#include "igm/layout/sizing.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/topology/open_cut.h"

using namespace igm;

namespace {

struct Config {
  std::string name;
  QuadLayout layout;
  int genus = 0, loops = 0;
};

QuadLayout closed_layout(int g, LayoutKind kind, int rows = 0) {
  const auto corners = canonical_polygon(g);
  LayoutOptions o;
  o.kind = kind;
  o.rows = rows;
  return make_layout(corners, polygon_centre(corners), canonical_side_mates(g), o);
}

// The layouts of the open pipeline: the open cut of a generated mesh of genus g with b loops.
QuadLayout open_layout(int g, int b, LayoutKind kind) {
  GenerateOptions go;
  go.genus = g;
  go.boundaries = b;
  go.faces = 300 + 250 * g + 60 * b;
  go.seed = 7;
  const SurfaceSet set = validate_surfaces(generate_mesh(go));
  const OpenCut cut = cut_open_surface(set.components.at(0));
  std::vector<int> mates, labels;
  for (const OpenSide& s : cut.sides) {
    mates.push_back(s.mate);
    labels.push_back(cut.disk_to_surface[s.disk_vertices.front()]);
  }
  const auto corners = schema_polygon(static_cast<int>(cut.sides.size()));
  LayoutOptions o;
  o.kind = kind;
  return make_layout(corners, polygon_centre(corners), mates, o, labels);
}

std::vector<Config> configs() {
  std::vector<Config> out;
  for (int g = 1; g <= 4; ++g) {
    for (int rows = 1; rows <= std::max(1, g); ++rows)
      out.push_back({"spread g" + std::to_string(g) + " rows " + std::to_string(rows), closed_layout(g, LayoutKind::Spread, rows), g, 0});
    out.push_back({"kite g" + std::to_string(g), closed_layout(g, LayoutKind::Kite), g, 0});
    out.push_back({"paper g" + std::to_string(g), closed_layout(g, LayoutKind::Paper), g, 0});
  }
  for (auto [g, b] : {std::pair{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 1}, {1, 2}, {2, 1}, {2, 3}})
    for (LayoutKind kind : {LayoutKind::Spread, LayoutKind::Kite}) {
      out.push_back({std::string("open ") + to_string(kind) + " g" + std::to_string(g) + " b" + std::to_string(b),
                     open_layout(g, b, kind), g, b});
    }
  return out;
}

std::vector<std::array<int, 2>> quad_sizes(const QuadLayout& L, const std::vector<int>& chord_count) {
  std::vector<std::array<int, 2>> size(L.quads.size());
  for (std::size_t q = 0; q < L.quads.size(); ++q)
    for (int k = 0; k < 2; ++k) size[q][k] = chord_count[L.chord[L.surface_edge[L.quad_edge[q][k]]]];
  return size;
}

std::int64_t total_quads(const QuadLayout& L, const std::vector<int>& chord_count) {
  std::int64_t n = 0;
  for (const auto& s : quad_sizes(L, chord_count)) n += static_cast<std::int64_t>(s[0]) * s[1];
  return n;
}

// The certifier's quad check on the grid, with the surface's genus and loops expected.
certify::Report certify_grid(const Config& c, const std::vector<int>& chord_count) {
  const LayoutGrid grid = layout_grid(c.layout, quad_sizes(c.layout, chord_count));
  certify::QuadInput in;
  in.quads = grid.quads;
  in.num_vertices = static_cast<std::int64_t>(grid.vertices.size());
  certify::Options o;
  o.allow_boundary = c.loops > 0;
  o.expected_genus = c.genus;
  if (c.loops > 0) o.expected_boundary_loops = c.loops;
  return certify::certify_quads(in, o);
}

}  // namespace

TEST_CASE("layout_grid: a b quads per layout quad, shared vertices: V - E + F of the glued surface") {
  // Genus 2 spread at counts 2: 4 x #layout quads quads; a closed quad mesh has E = 2F, so
  // V = chi + F = -2 + F.
  const QuadLayout L = closed_layout(2, LayoutKind::Spread);
  const LayoutGrid grid = layout_grid(L, std::vector<std::array<int, 2>>(L.quads.size(), {2, 2}));
  CHECK(grid.quads.size() == 4 * L.quads.size());
  CHECK(static_cast<std::int64_t>(grid.vertices.size()) == -2 + static_cast<std::int64_t>(grid.quads.size()));
  // Every vertex's first occurrence is a point of its quad's rectangle; corners name layout vertices.
  for (const LayoutGridVertex& v : grid.vertices) {
    CHECK(v.i >= 0);
    CHECK(v.i <= 2);
    CHECK(v.j >= 0);
    CHECK(v.j <= 2);
    CHECK((v.layout_vertex >= 0) == ((v.i % 2 == 0) && (v.j % 2 == 0)));
  }
  CHECK_THROWS_AS(layout_grid(L, {}), Error);
  CHECK_THROWS_AS(layout_grid(L, std::vector<std::array<int, 2>>(L.quads.size(), {0, 1})), Error);
}

TEST_CASE("sizing floor: every layout's chord minimum gives a manifold quad mesh, and one less on any chord does not") {
  std::mt19937_64 rng(47);
  for (const Config& c : configs()) {
    CAPTURE(c.name);
    const QuadLayout& L = c.layout;
    const std::vector<int> minimum = minimum_chord_counts(L);
    // Sufficient: at the minimum, and at random counts up to two above it.
    const certify::Report at_min = certify_grid(c, minimum);
    CHECK_MESSAGE(at_min.valid(), certify::summary(at_min));
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<int> count = minimum;
      for (int& n : count) n += static_cast<int>(rng() % 3);
      CHECK(certify_grid(c, count).valid());
    }
    // Needed: one chord below its minimum, the others at theirs, fails (of parallel layout edges
    // one may stay a single quad edge: which one is the floor's choice, so not with the others
    // raised).
    for (int ch = 0; ch < L.num_chords; ++ch) {
      if (minimum[ch] == 1) continue;
      CAPTURE(ch);
      std::vector<int> count = minimum;
      count[ch] = minimum[ch] - 1;
      CHECK_FALSE(certify_grid(c, count).valid());
    }
  }
}

TEST_CASE("sizing floor: the least quad count of any manifold grid is the floor's (every count 1..3 of up to 8 chords)") {
  for (const Config& c : configs()) {
    const QuadLayout& L = c.layout;
    if (L.num_chords > 8) continue;
    CAPTURE(c.name);
    const std::vector<int> minimum = minimum_chord_counts(L);
    std::int64_t least = -1;
    std::vector<int> count(L.num_chords, 1);
    // Odometer over {1, 2, 3}^chords: at most 3^8 grids.
    for (bool more = true; more;) {
      const std::int64_t n = total_quads(L, count);
      if ((least < 0 || n < least) && certify_grid(c, count).valid()) least = n;
      more = false;
      for (int& x : count) {
        if (x < 3) {
          ++x;
          more = true;
          break;
        }
        x = 1;
      }
    }
    CHECK(least == total_quads(L, minimum));
  }
}
