// Topology stage measurements: time and mesh growth of cut_to_canonical_disk.
// Usage: igm_bench_topology [shared_dir] [--normal-form-all] [--crosses|--rounds] [--serial]
//                           [--no-tighten] [--no-slides] [--congestion-rounds N] [--nf-roots N]
//                           [--no-locality-order] [--restarts N] [--only NAME|g3|g10|g20|g40]
// Growth is broken down by source: crossings, Steiner, band, chord and pre-condition splits, and
// the normal form's rounds (marked "(crosses)" where the crosses construction won, "raced" where a
// lone root candidate ran both constructions side by side) and chord splits, and "slides k/t" (step
// 3c: the k handle slides of the kept normal form, 0 if the rounds or crosses were kept, of t
// drawn to choose them; "failed" where a step could draw none; "after" where it ran after the
// rounds or crosses, past CutOptions::slides_budget, for their growth). The normal form is
// measured on every mesh; --normal-form-all is accepted and changes nothing (it added the 1M-face
// g20's, ~10 s before stop 27, 4.6-5 s since); --only runs one mesh, with and without it;
// --nf-roots N sets CutOptions::normal_form_roots (default: automatic; cheese gets 1, --nf-roots 11
// is what it had before stop 23); --crosses / --rounds use that construction alone; --serial
// evaluates the root candidates on one thread (CutOptions::parallel = false; same results);
// --no-tighten skips the loop tightening (CutOptions::tighten = false), for comparison;
// --no-slides turns step 3c off (CutOptions::slides = 0);
// --congestion-rounds N sets CutOptions::congestion_rounds (0: off; default: automatic);
// --restarts N sets CutOptions::restarts (default 0; -1: automatic): the line then shows
// "restarts k/n" (the run kept, 0 the first, of the n made on shuffled vertex ids);
// --no-locality-order runs the steps in the input's own vertex order on every mesh
// (CutOptions::locality_order_min_vertices = -1; by default meshes of >= 32,768 vertices, here the
// 1M-face g20, are renumbered first: the line then ends with "renumbered"). The line without the
// normal form shows "congestion r/n" (the round kept, of the n recomputed bases).
// Under each line: the ring-capacity floor (topology/ring_bound.h) at the chosen root, the vertices
// any loop system through it must add; without the normal form on meshes of <= 3,000 vertices also
// the least floor over every root. --only g40 runs a generated genus 40 on 1M faces (not in the
// default run: ~12 s with the normal form), which gets the crosses alone (genus >= 30); --only g10
// a generated genus 10 on 200k faces (not in the default run: ~12 s with the normal form), past
// the slides' budget, where they run after the rounds for the rounds' growth.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "igm/core/error.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/topology/cut_to_canonical_disk.h"
#include "igm/topology/ring_bound.h"

using namespace igm;

namespace {
struct Input {
  TriMesh mesh;
  std::vector<Vec3d> positions;
};

bool read_off(const std::filesystem::path& p, Input& out) {
  try {
    ValidMesh v = load_mesh(p);
    out.mesh = std::move(v.mesh);
    out.positions = std::move(v.positions);
    return true;
  } catch (const Error&) {
    return false;
  }
}

Input generated(int genus, long faces) {
  GenerateOptions o;
  o.genus = genus;
  o.faces = faces;
  o.seed = 3;
  PolygonSoup s = generate_closed_mesh(o);
  std::vector<std::array<int, 3>> t;
  for (std::size_t f = 0; f < s.num_faces(); ++f) {
    const auto* c = &s.corners[s.face_begin[f]];
    t.push_back({int(c[0]), int(c[1]), int(c[2])});
  }
  return {TriMesh::from_triangles(static_cast<int>(s.positions.size()), t), s.positions};
}

CutOptions::Construction construction = CutOptions::Construction::Best;  // --crosses / --rounds
bool parallel = true;                                                      // --serial: one thread
bool tighten = true;                                                       // --no-tighten
int locality_min = CutOptions{}.locality_order_min_vertices;  // --no-locality-order: -1
int congestion_rounds = -1;                                                // --congestion-rounds N
int slides = -1;                                                           // --no-slides: 0
int nf_roots = -1;                                                         // --nf-roots N
int restarts = 0;                                                          // --restarts N

void run(const std::string& name, const Input& in, bool normal_form) {
  CutOptions o;
  o.normal_form = normal_form;
  o.construction = construction;
  o.parallel = parallel;
  o.tighten = tighten;
  o.congestion_rounds = congestion_rounds;
  o.slides = slides;
  o.normal_form_roots = nf_roots;
  o.restarts = restarts;
  o.locality_order_min_vertices = locality_min;
  try {
    CutResult r = cut_to_canonical_disk(in.mesh, in.positions, o);
    const auto& s = r.stats;
    std::printf("%-24s g=%-4d F=%-8d nf=%d  V %8d -> %8d (+%6.1f%%) | crossings %6d steiner %5d band %4d chord %5d"
                " collapsed %5d precond %6d | rounds %3d%s chords %6d - %6d | slides %2d/%-4lld%s%s redrawn %2d | roots %2d"
                " congestion %2d/%-2d | %7.3f s (basis %.3f, detach %.3f, cut %.3f)%s%s\n",
                name.c_str(), s.genus, s.faces_before, normal_form ? 1 : 0, s.vertices_before, s.vertices_after,
                100.0 * (s.vertices_after - s.vertices_before) / s.vertices_before, s.crossings, s.steiner_vertices,
                s.band_splits, s.chord_splits, s.collapsed, s.precondition_splits, s.normal_form_rounds, s.crosses ? (s.raced ? " (crosses, raced)" : " (crosses)") : s.raced ? " (raced)" : "", s.round_chord_splits, s.straightened,
                s.slides, s.slide_trials, s.slides_failed ? " failed" : "", s.slides_after ? " after" : "", s.redrawn,
                s.roots_tried,
                s.congestion_best_round, s.congestion_rounds, s.seconds_total,
                s.seconds_basis, s.seconds_detach, s.seconds_cut, s.locality_ordered ? " renumbered" : "",
                s.restarts > 0 ? (" | restarts " + std::to_string(s.restart_kept) + "/" + std::to_string(s.restarts)).c_str()
                               : "");
    // The ring-capacity floor (topology/ring_bound.h): what any loop system through this root must
    // add, and on small meshes the least over every root.
    const RingBound floor_here = ring_capacity_bound(in.mesh, r.root);
    std::printf("%-24s        floor at root %d: >= %lld added", "", r.root, floor_here.new_vertices);
    if (!normal_form && in.mesh.num_vertices() <= 3000) {
      long long least = floor_here.new_vertices;
      for (int v = 0; v < in.mesh.num_vertices(); ++v) least = std::min(least, ring_capacity_bound(in.mesh, v).new_vertices);
      std::printf(" (least over all roots: %lld)", least);
    }
    std::printf("\n");
  } catch (const Error& e) {
    std::printf("%-24s nf=%d error: %s\n", name.c_str(), normal_form ? 1 : 0, e.what());
  }
  std::fflush(stdout);
}
}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path shared = "../shared";
  std::string only;  // --only NAME: that shared mesh alone, with the normal form too
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--normal-form-all") == 0) continue;  // the default since stop 27
    else if (std::strcmp(argv[i], "--crosses") == 0) construction = CutOptions::Construction::Crosses;
    else if (std::strcmp(argv[i], "--rounds") == 0) construction = CutOptions::Construction::Rounds;
    else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc) only = argv[++i];
    else if (std::strcmp(argv[i], "--serial") == 0) parallel = false;
    else if (std::strcmp(argv[i], "--no-tighten") == 0) tighten = false;
    else if (std::strcmp(argv[i], "--no-slides") == 0) slides = 0;
    else if (std::strcmp(argv[i], "--no-locality-order") == 0) locality_min = -1;
    else if (std::strcmp(argv[i], "--congestion-rounds") == 0 && i + 1 < argc) congestion_rounds = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--nf-roots") == 0 && i + 1 < argc) nf_roots = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--restarts") == 0 && i + 1 < argc) restarts = std::atoi(argv[++i]);
    else shared = argv[i];
  }
  for (const char* name : {"eight", "joint", "helmet", "elephant", "anchor", "couplingdown", "cheese"}) {
    if (!only.empty() && only != name) continue;
    Input in;
    if (!read_off(shared / "meshes" / "clean" / (std::string(name) + ".off"), in)) {
      std::printf("%-26s skipped: not found under %s\n", name, shared.c_str());
      continue;
    }
    run(name, in, false);
    run(name, in, true);
  }
  if (!only.empty() && only != "g3" && only != "g10" && only != "g20" && only != "g40") return 0;
  if (only.empty() || only == "g3") {
    Input in = generated(3, 52000);
    run("generated g3 52k faces", in, false);
    run("generated g3 52k faces", in, true);
  }
  if (only.empty() || only == "g20") {
    Input in = generated(20, 1000000);
    run("generated g20 1M faces", in, false);
    run("generated g20 1M faces", in, true);
  }
  if (only == "g10") {
    Input in = generated(10, 200000);
    run("generated g10 200k faces", in, false);
    run("generated g10 200k faces", in, true);
  }
  if (only == "g40") {
    Input in = generated(40, 1000000);
    run("generated g40 1M faces", in, false);
    run("generated g40 1M faces", in, true);
  }
  return 0;
}
