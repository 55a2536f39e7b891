// Feature edges on integer isolines (igm-certify --features, Options::feature_edges): the features
// file reader, the exact check on a folded two-square sheet, errors, unchanged bytes without
// features, and a pipeline-made cube whose 12 sharp edges the field layout puts on isolines.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>
#include <vector>

#include "certify/certify.h"
#include "test_data.h"
#include "cli_files.h"

namespace fs = std::filesystem;
using namespace igm::certify;
using certify_test::slurp;
using certify_test::write;

namespace {

// Two unit squares folded along the crease x = 1 (vertices 1 and 4, a right angle in space). In
// UV the left square is [0,1]^2, the right one [1,2]x[0,1] mapped by R(x, y) + (3, 2) (R: +90
// degrees), so the crease lies on u = 1 in the left faces' chart and on v = 3 in the right ones'.
// A valid IGM with boundary (--boundary): checks 1-4 pass.
const std::string kCrease = R"OBJ(# two unit squares folded along the crease x = 1 (vertices 1 and 4); the right square's chart is
# rotated by +90 degrees and translated by (3, 2): there the crease lies on v = 3
v 0 0 0
v 1 0 0
v 1 0 1
v 0 1 0
v 1 1 0
v 1 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 0
vt 1 1
vt 0 1
vt 3 3
vt 3 4
vt 2 4
vt 3 3
vt 2 4
vt 2 3
f 1/1 2/2 5/3
f 1/4 5/5 4/6
f 2/7 3/8 6/9
f 2/10 6/11 5/12
)OBJ";

// The crease's upper vertex 4 moved to u = 1 + 1/3 in both charts (left (4/3, 1), right
// (2, 10/3)): still a valid IGM (a flat boundary vertex may sit anywhere on its isoline v = 1),
// but the crease 1-4 leaves its isolines in both faces.
std::string moved() {
  std::string s = kCrease;
  for (auto [from, to] : {std::pair<std::string, std::string>{"vt 1 1\n", "vt 4/3 1\n"}, {"vt 2 3\n", "vt 2 10/3\n"}})
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  return s;
}

// Vertex 5 moved to (2, 4/3) (right chart (5/3, 4)): the boundary edge 4-5 leaves its isoline.
std::string off_boundary() {
  std::string s = kCrease;
  for (std::size_t p = s.find("vt 2 4\n"); p != std::string::npos; p = s.find("vt 2 4\n", p)) s.replace(p, 7, "vt 5/3 4\n");
  return s;
}

// The certificates igm-certify --boundary wrote for kCrease and off_boundary() (as crease.obj and
// offbnd.obj) before the features check existed: without --features the bytes must stay these.
const std::string kCreaseJson = R"J({
  "certifier": "igm-certify",
  "format_version": 1,
  "source": "crease.obj",
  "mode": "igm",
  "verdict": "valid",
  "valid": true,
  "exit_code": 0,
  "index_base": 0,
  "error": null,
  "mesh": {"vertices": 6, "edges": 9, "faces": 4, "euler_characteristic": 1, "genus": 0, "boundary_edges": 6, "boundary_loops": 1, "connected_components": 1},
  "components": [
    {"first_vertex": 0, "vertices": 6, "edges": 9, "faces": 4, "boundary_edges": 6, "boundary_loops": 1, "euler_characteristic": 1, "genus": 0, "poincare_hopf_sum": 4, "poincare_hopf_expected": 4}
  ],
  "checks": [
    {"id": 1, "name": "topology", "status": "pass", "pass": true,
     "counts": {"vertices": 6, "edges": 9, "faces": 4, "euler_characteristic": 1, "boundary_edges": 6, "nonmanifold_edges": 0, "inconsistently_oriented_edges": 0, "nonmanifold_vertices": 0, "faces_repeating_a_vertex": 0, "unreferenced_vertices": 0, "connected_components": 1, "boundary_vertices": 6, "boundary_loops": 1, "genus": 0},
     "offending": 0, "witnesses_shown": 0, "note": "",
     "witnesses": []},
    {"id": 2, "name": "uv_orientation", "status": "pass", "pass": true,
     "counts": {"faces": 4, "positive": 4, "flipped": 0, "degenerate": 0},
     "offending": 0, "witnesses_shown": 0, "note": "",
     "witnesses": []},
    {"id": 3, "name": "transitions", "status": "pass", "pass": true,
     "counts": {"interior_edges_checked": 3, "rigid": 3, "non_rigid": 0, "no_rotation_matches": 0, "translation_not_integer": 0, "zero_length_both_sides": 0, "edges_not_interior": 6, "boundary_edges_checked": 6, "boundary_edges_on_isoline": 6, "boundary_edges_off_isoline": 0},
     "histogram": {"name": "rotation_k", "bins": {"0": 2, "1": 1}},
     "offending": 0, "witnesses_shown": 0, "note": "k maps the chart of the face left of u->v (u<v) onto the chart of the face right of it; boundary edges: u or v constant and integer along the edge in its face's chart",
     "witnesses": []},
    {"id": 4, "name": "cones", "status": "pass", "pass": true,
     "counts": {"vertices_determined": 6, "vertices_nonrigid_ring": 0, "vertices_undetermined": 0, "cones": 0, "cones_off_integer": 0, "nonrigid_ring_cones": 0, "nonrigid_ring_cones_off_integer": 0, "cones_off_integer_total": 0, "nonpositive_index": 0, "poincare_hopf_sum": 4, "poincare_hopf_expected": 4, "poincare_hopf_checked": 1, "transport_inconsistent": 0, "boundary_vertices": 6, "boundary_vertices_determined": 6, "boundary_corners": 4, "boundary_corners_off_integer": 0, "boundary_nonpositive_index": 0},
     "histogram": {"name": "vertex_index_k", "bins": {}},
     "boundary_histogram": {"name": "boundary_index_k", "bins": {"1": 4, "2": 2}},
     "offending": 0, "witnesses_shown": 0, "note": "determined: ring of rigid edges, exact index; nonrigid_ring: ring crosses edges that failed check 3, index computed with the nearest rotation there (reported, not a proof); undetermined: non-manifold ring, zero-length or tied edge, or antiparallel corner; boundary vertices: angle k*pi/2 over the fan between their boundary edges, flat at k = 2, exact when both boundary edges are axis-parallel",
     "witnesses": []}
  ]
}
)J";
const std::string kOffBoundaryJson = R"J({
  "certifier": "igm-certify",
  "format_version": 1,
  "source": "offbnd.obj",
  "mode": "igm",
  "verdict": "invalid",
  "valid": false,
  "exit_code": 1,
  "index_base": 0,
  "error": null,
  "mesh": {"vertices": 6, "edges": 9, "faces": 4, "euler_characteristic": 1, "genus": 0, "boundary_edges": 6, "boundary_loops": 1, "connected_components": 1},
  "components": [
    {"first_vertex": 0, "vertices": 6, "edges": 9, "faces": 4, "boundary_edges": 6, "boundary_loops": 1, "euler_characteristic": 1, "genus": 0, "poincare_hopf_sum": null, "poincare_hopf_expected": 4}
  ],
  "checks": [
    {"id": 1, "name": "topology", "status": "pass", "pass": true,
     "counts": {"vertices": 6, "edges": 9, "faces": 4, "euler_characteristic": 1, "boundary_edges": 6, "nonmanifold_edges": 0, "inconsistently_oriented_edges": 0, "nonmanifold_vertices": 0, "faces_repeating_a_vertex": 0, "unreferenced_vertices": 0, "connected_components": 1, "boundary_vertices": 6, "boundary_loops": 1, "genus": 0},
     "offending": 0, "witnesses_shown": 0, "note": "",
     "witnesses": []},
    {"id": 2, "name": "uv_orientation", "status": "pass", "pass": true,
     "counts": {"faces": 4, "positive": 4, "flipped": 0, "degenerate": 0},
     "offending": 0, "witnesses_shown": 0, "note": "",
     "witnesses": []},
    {"id": 3, "name": "transitions", "status": "fail", "pass": false,
     "counts": {"interior_edges_checked": 3, "rigid": 3, "non_rigid": 0, "no_rotation_matches": 0, "translation_not_integer": 0, "zero_length_both_sides": 0, "edges_not_interior": 6, "boundary_edges_checked": 6, "boundary_edges_on_isoline": 5, "boundary_edges_off_isoline": 1},
     "histogram": {"name": "rotation_k", "bins": {"0": 2, "1": 1}},
     "offending": 1, "witnesses_shown": 1, "note": "k maps the chart of the face left of u->v (u<v) onto the chart of the face right of it; boundary edges: u or v constant and integer along the edge in its face's chart",
     "witnesses": [
       {"kind": "edge", "ids": [4, 5], "reason": "boundary edge not on an integer isoline (u or v constant and integer)", "values": {"face": "3", "uv_u": "(2, 3)", "uv_v": "(5/3, 4)"}}
     ]},
    {"id": 4, "name": "cones", "status": "incomplete", "pass": false,
     "counts": {"vertices_determined": 4, "vertices_nonrigid_ring": 0, "vertices_undetermined": 2, "cones": 0, "cones_off_integer": 0, "nonrigid_ring_cones": 0, "nonrigid_ring_cones_off_integer": 0, "cones_off_integer_total": 0, "nonpositive_index": 0, "poincare_hopf_sum": 0, "poincare_hopf_expected": 0, "poincare_hopf_checked": 0, "transport_inconsistent": 0, "boundary_vertices": 6, "boundary_vertices_determined": 4, "boundary_corners": 3, "boundary_corners_off_integer": 0, "boundary_nonpositive_index": 0},
     "histogram": {"name": "vertex_index_k", "bins": {}},
     "boundary_histogram": {"name": "boundary_index_k", "bins": {"1": 3, "2": 1}},
     "offending": 2, "witnesses_shown": 2, "note": "determined: ring of rigid edges, exact index; nonrigid_ring: ring crosses edges that failed check 3, index computed with the nearest rotation there (reported, not a proof); undetermined: non-manifold ring, zero-length or tied edge, or antiparallel corner; boundary vertices: angle k*pi/2 over the fan between their boundary edges, flat at k = 2, exact when both boundary edges are axis-parallel",
     "witnesses": [
       {"kind": "vertex", "ids": [4], "reason": "boundary angle undetermined", "values": {"why": "incoming boundary edge not parallel to an axis"}},
       {"kind": "vertex", "ids": [5], "reason": "boundary angle undetermined", "values": {"why": "outgoing boundary edge not parallel to an axis"}}
     ]}
  ]
}
)J";

Options with_features(std::vector<FeatureEdge> f) {
  Options o;
  o.allow_boundary = true;
  o.feature_edges = std::move(f);
  return o;
}

std::string value(const Witness& w, const std::string& key) {
  for (const auto& [k, v] : w.values)
    if (k == key) return v;
  return "<absent>";
}

fs::path tmp_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("igm_certify_features_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

struct Run {
  int code = -1;
  std::string out, err;
};

// Runs `command` (a shell command line) in dir.
Run in_dir(const fs::path& dir, const std::string& command) {
  const std::string cmd = "cd \"" + dir.string() + "\" && " + command + " > stdout.txt 2> stderr.txt";
  const int st = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.out = slurp(dir / "stdout.txt");
  r.err = slurp(dir / "stderr.txt");
  return r;
}

std::string certify_cmd(const std::string& args) { return std::string("\"") + IGM_CERTIFY_CLI_PATH + "\" " + args; }

bool has(const std::string& s, const std::string& x) { return s.find(x) != std::string::npos; }

}  // namespace

TEST_CASE("features file: pairs, comments, blank lines, CRLF, and malformed lines named by line") {
  const FeatureReadResult r = read_feature_edges("# creases\n\n1 4\r\n  7\t 12  \n   # indented comment\n0 3");
  REQUIRE(r.ok);
  REQUIRE(r.edges.size() == 3);
  CHECK(r.edges[0].a == 1);
  CHECK(r.edges[0].b == 4);
  CHECK(r.edges[0].line == 3);
  CHECK(r.edges[1].a == 7);
  CHECK(r.edges[1].b == 12);
  CHECK(r.edges[1].line == 4);
  CHECK(r.edges[2].line == 6);
  CHECK(read_feature_edges("").ok);
  CHECK(read_feature_edges("").edges.empty());
  for (const char* bad : {"1 4 5", "1", "1 x", "-1 4", "+1 4", "1,4", "1 4 # crease", "1.0 4", "3000000000 1", "14"}) {
    const FeatureReadResult b = read_feature_edges(std::string("0 1\n# c\n") + bad + "\n2 3\n");
    CHECK_MESSAGE(!b.ok, bad);
    CHECK(b.error_line == 3);
    CHECK(has(b.error, "line 3"));
    CHECK(b.edges.empty());
  }
  const FeatureReadResult missing = read_feature_edges_file("/nonexistent/features.txt");
  CHECK(!missing.ok);
  CHECK(has(missing.error, "cannot read"));
}

TEST_CASE("features: a crease on u = 1 in one chart and v = 3 in the other passes") {
  const Report r = certify_igm_text(kCrease, with_features({{1, 4, 1}, {4, 1, 2}, {0, 1, 3}, {2, 5, 4}}));
  REQUIRE(r.features);
  CHECK(r.valid());
  CHECK(r.features->passed());
  CHECK(r.features->id == 6);
  CHECK(r.features->count("feature_pairs") == 4);
  CHECK(r.features->count("duplicates") == 1);        // 4 1 is 1 4
  CHECK(r.features->count("edges_checked") == 3);
  CHECK(r.features->count("edges_on_isoline") == 3);
  CHECK(r.features->count("faces_checked") == 4);     // the crease in 2 faces, boundary edges in 1
  CHECK(r.features->witnesses.empty());
  // An empty list checks nothing and passes; no list: no section.
  CHECK(certify_igm_text(kCrease, with_features({})).features->count("edges_checked") == 0);
  Options plain;
  plain.allow_boundary = true;
  CHECK(!certify_igm_text(kCrease, plain).features);
}

TEST_CASE("features: the crease moved to u = 1 + 1/3 fails, the edge and both faces named") {
  const Report r = certify_igm_text(moved(), with_features({{0, 1, 1}, {1, 4, 2}}));
  REQUIRE(r.features);
  for (int id = 1; id <= 4; ++id) CHECK(r.check(id)->passed());  // the IGM itself is valid
  CHECK(r.verdict == Verdict::Invalid);
  CHECK(exit_code(r) == 1);
  CHECK(r.features->status == Status::Fail);
  CHECK(r.features->count("edges_checked") == 2);
  CHECK(r.features->count("edges_off_isoline") == 1);
  CHECK(r.features->count("faces_off_isoline") == 2);
  CHECK(r.features->offending == 2);
  REQUIRE(r.features->witnesses.size() == 2);
  const Witness& a = r.features->witnesses[0];
  CHECK(a.kind == "edge");
  CHECK(a.ids == std::vector<std::int64_t>{1, 4});
  CHECK(value(a, "face") == "0");
  CHECK(value(a, "uv_u") == "(1, 0)");
  CHECK(value(a, "uv_v") == "(4/3, 1)");
  CHECK(value(a, "condition") == "u differs; v differs");
  CHECK(value(a, "line") == "2");
  const Witness& b = r.features->witnesses[1];
  CHECK(value(b, "face") == "3");
  CHECK(value(b, "uv_u") == "(3, 3)");
  CHECK(value(b, "uv_v") == "(2, 10/3)");
  // The summary and the JSON say so.
  CHECK(has(summary(r), "features=fail 1/2 on isolines"));
  const std::string j = to_json(r);
  CHECK(has(j, "\"features\": {\"id\": 6, \"name\": \"features\", \"status\": \"fail\""));
  CHECK(has(j, "\"uv_v\": \"(4/3, 1)\", \"condition\": \"u differs; v differs\""));
}

TEST_CASE("features: same u (or v) but not an integer fails with that condition") {
  // Shift the whole left chart by 1/2 in u and the right chart by 1/2 in v: a valid IGM only up to
  // the transitions (check 3 fails), but the crease keeps u = 3/2 and v = 7/2, equal and not integer.
  std::string s = kCrease;
  const std::vector<std::pair<std::string, std::string>> shift = {
      {"vt 0 0\n", "vt 1/2 0\n"}, {"vt 1 0\n", "vt 3/2 0\n"}, {"vt 1 1\n", "vt 3/2 1\n"}, {"vt 0 1\n", "vt 1/2 1\n"},
      {"vt 3 3\n", "vt 3 7/2\n"}, {"vt 3 4\n", "vt 3 9/2\n"}, {"vt 2 4\n", "vt 2 9/2\n"}, {"vt 2 3\n", "vt 2 7/2\n"}};
  for (const auto& [from, to] : shift)
    for (std::size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  const Report r = certify_igm_text(s, with_features({{1, 4, 0}}));
  REQUIRE(r.features);
  REQUIRE(r.features->witnesses.size() == 2);
  CHECK(value(r.features->witnesses[0], "uv_u") == "(3/2, 0)");
  CHECK(value(r.features->witnesses[0], "condition") == "u equal, not integer; v differs");
  CHECK(value(r.features->witnesses[1], "condition") == "u differs; v equal, not integer");
  CHECK(value(r.features->witnesses[1], "line") == "<absent>");  // given in memory
}

TEST_CASE("features: a pair that is not an edge or a vertex out of range is unreadable") {
  for (const auto& [pair, what] : std::vector<std::pair<FeatureEdge, std::string>>{
           {{0, 5, 7}, "features line 7: pair \"0 5\" is not an edge of the mesh"},
           {{3, 3, 2}, "features line 2: pair \"3 3\" is not an edge of the mesh"},
           {{1, 6, 9}, "features line 9: pair \"1 6\": vertex id 6 out of range (the mesh has 6 vertices, ids 0..5)"},
           {{2, 0, 0}, "feature edge 1: pair \"2 0\" is not an edge of the mesh"}}) {
    const Report r = certify_igm_text(kCrease, with_features({{1, 4, 1}, pair}));
    CHECK(r.verdict == Verdict::Unreadable);
    CHECK(exit_code(r) == 2);
    CHECK(r.error == what);
    CHECK(!r.features);
  }
  // In memory too (IgmInput): the same rule.
  IgmInput in;
  in.faces = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& [u, v] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
    in.corner_uv.push_back({mpq_class(u), mpq_class(v)});
  Options o = with_features({{1, 3, 0}});
  CHECK(certify_igm(in, o).verdict == Verdict::Unreadable);
  o.feature_edges = std::vector<FeatureEdge>{{0, 1, 0}, {2, 3, 0}, {0, 2, 0}};
  const Report ok = certify_igm(in, o);
  REQUIRE(ok.features);
  for (int id = 1; id <= 4; ++id) CHECK(ok.check(id)->passed());
  CHECK(ok.features->count("edges_on_isoline") == 2);  // the square's sides; its diagonal is not
  CHECK(ok.features->count("edges_off_isoline") == 1);
  CHECK(ok.verdict == Verdict::Invalid);
}

TEST_CASE("cli --features: exit 0 on the crease, 1 when moved (edge named), 2 on bad pairs and files") {
  const fs::path dir = tmp_dir("cli");
  write(dir / "crease.obj", kCrease);
  write(dir / "moved.obj", moved());
  write(dir / "crease.txt", "# the fold\n1 4\n\n# two boundary edges\n0 1\n5 2\n");
  Run r = in_dir(dir, certify_cmd("--boundary --features crease.txt crease.obj"));
  CHECK(r.code == 0);
  CHECK(has(r.out, "\"edges_checked\": 3, \"edges_on_isoline\": 3, \"edges_off_isoline\": 0"));
  CHECK(has(r.err, "features=pass 3/3 on isolines"));

  r = in_dir(dir, certify_cmd("--boundary --features crease.txt moved.obj"));
  CHECK(r.code == 1);
  CHECK(has(r.out, "\"verdict\": \"invalid\""));
  CHECK(has(r.out, "{\"kind\": \"edge\", \"ids\": [1, 4], \"reason\": \"feature edge not on an integer isoline"));
  CHECK(has(r.out, "\"uv_v\": \"(4/3, 1)\""));
  CHECK(has(r.out, "\"line\": \"2\""));

  write(dir / "notedge.txt", "1 4\n0 5\n");
  r = in_dir(dir, certify_cmd("--boundary --features notedge.txt crease.obj"));
  CHECK(r.code == 2);
  CHECK(has(r.out, "\"verdict\": \"unreadable\""));
  CHECK(has(r.err, "features line 2: pair \"0 5\" is not an edge of the mesh"));

  write(dir / "range.txt", "1 40\n");
  r = in_dir(dir, certify_cmd("--boundary --features range.txt crease.obj"));
  CHECK(r.code == 2);
  CHECK(has(r.err, "features line 1: pair \"1 40\": vertex id 40 out of range"));

  write(dir / "malformed.txt", "1 4\n0 1 2\n");
  r = in_dir(dir, certify_cmd("--boundary --features malformed.txt crease.obj"));
  CHECK(r.code == 2);
  CHECK(has(r.out, "\"verdict\": \"unreadable\""));
  CHECK(has(r.err, "features file 'malformed.txt': line 2: expected two vertex ids"));
  r = in_dir(dir, certify_cmd("--boundary --features absent.txt crease.obj"));
  CHECK(r.code == 2);
  CHECK(has(r.err, "cannot read file 'absent.txt'"));
  for (const char* bad : {"--features", "--quad --features crease.txt crease.obj"}) {
    r = in_dir(dir, certify_cmd(bad));
    CHECK_MESSAGE(r.code == 2, bad);
  }
}

TEST_CASE("cli without --features: the certificate's bytes are those written before the check existed") {
  const fs::path dir = tmp_dir("bytes");
  write(dir / "crease.obj", kCrease);
  write(dir / "offbnd.obj", off_boundary());
  Run r = in_dir(dir, certify_cmd("--boundary crease.obj"));
  CHECK(r.code == 0);
  CHECK(r.out == kCreaseJson);
  CHECK(r.err == "igm-certify: VALID igm crease.obj: V=6 E=9 F=4 genus=0 boundary_loops=1; 1:topology=pass; "
                 "2:uv_orientation=pass; 3:transitions=pass; 4:cones=pass\n");
  r = in_dir(dir, certify_cmd("--boundary offbnd.obj"));  // the boundary witness shares the isoline test
  CHECK(r.code == 1);
  CHECK(r.out == kOffBoundaryJson);
  // With --features the same text up to the checks, then the features section.
  write(dir / "f.txt", "1 4\n");
  r = in_dir(dir, certify_cmd("--boundary --features f.txt crease.obj"));
  CHECK(r.code == 0);
  const std::string head = kCreaseJson.substr(0, kCreaseJson.size() - 3);  // without "\n}\n"
  const std::string section = ",\n  \"features\": {\"id\": 6,";
  CHECK(r.out.compare(0, head.size(), head) == 0);
  CHECK(r.out.compare(head.size(), section.size(), section) == 0);
}

namespace {

// The OBJ's vertex positions and triangles (`v x y z`, `f a/ta b/tb c/tc`, 1-based), read by the
// test to choose the feature edges by geometry.
struct Mesh {
  std::vector<std::array<double, 3>> p;
  std::vector<std::array<int, 3>> f;
};

Mesh read_positions(const std::string& text) {
  Mesh m;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      std::array<double, 3> x{};
      ls >> x[0] >> x[1] >> x[2];
      m.p.push_back(x);
    } else if (tag == "f") {
      std::array<int, 3> t{};
      for (int& c : t) {
        std::string corner;
        ls >> corner;
        c = std::stoi(corner.substr(0, corner.find('/'))) - 1;
      }
      m.f.push_back(t);
    }
  }
  return m;
}

// Edges (u < v) whose two faces' normals make an angle above `degrees`.
std::vector<std::pair<int, int>> sharp_edges(const Mesh& m, double degrees) {
  std::map<std::pair<int, int>, std::vector<std::array<double, 3>>> normals;
  for (const auto& t : m.f) {
    const auto &a = m.p[t[0]], &b = m.p[t[1]], &c = m.p[t[2]];
    const std::array<double, 3> e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x /= len;
    for (int i = 0; i < 3; ++i) {
      const int u = t[i], v = t[(i + 1) % 3];
      normals[{std::min(u, v), std::max(u, v)}].push_back(n);
    }
  }
  std::vector<std::pair<int, int>> out;
  for (const auto& [e, ns] : normals) {
    REQUIRE(ns.size() == 2);
    const double d = ns[0][0] * ns[1][0] + ns[0][1] * ns[1][1] + ns[0][2] * ns[1][2];
    if (std::acos(std::max(-1.0, std::min(1.0, d))) > degrees * M_PI / 180) out.push_back(e);
  }
  return out;
}

}  // namespace

TEST_CASE("pipeline: igm run --layout field on the cube puts its 12 sharp edges on isolines, certified") {
  IGM_REQUIRE_DATA(data);
  const fs::path dir = tmp_dir("cube");
  const Run run = in_dir(dir, std::string("\"") + IGM_CLI_PATH + "\" run \"" + (data / "meshes/clean/cube.off").string() +
                                  "\" -o out --layout field");
  REQUIRE(run.code == 0);
  const std::string igm = slurp(dir / "out/cube.igm.exact");
  const Mesh m = read_positions(igm);
  const std::vector<std::pair<int, int>> sharp = sharp_edges(m, 60);
  REQUIRE(sharp.size() == 12);
  std::string features = "# the cube's sharp edges (dihedral angle > 60 degrees)\n";
  for (const auto& [u, v] : sharp) features += std::to_string(u) + " " + std::to_string(v) + "\n";
  write(dir / "sharp.txt", features);
  Run r = in_dir(dir, certify_cmd("--features sharp.txt out/cube.igm.exact"));
  CHECK(r.code == 0);
  CHECK(has(r.out, "\"edges_checked\": 12, \"edges_on_isoline\": 12, \"edges_off_isoline\": 0, \"faces_checked\": 24"));
  // The check discriminates on this output: a face diagonal (a flat edge) is on no isoline.
  const std::vector<std::pair<int, int>> flat = sharp_edges(m, -1);
  std::pair<int, int> diagonal{-1, -1};
  for (const auto& e : flat)
    if (std::find(sharp.begin(), sharp.end(), e) == sharp.end()) diagonal = e;
  REQUIRE(diagonal.first >= 0);
  write(dir / "diagonal.txt", features + std::to_string(diagonal.first) + " " + std::to_string(diagonal.second) + "\n");
  r = in_dir(dir, certify_cmd("--features diagonal.txt out/cube.igm.exact"));
  CHECK(r.code == 1);
  CHECK(has(r.out, "\"edges_checked\": 13, \"edges_on_isoline\": 12, \"edges_off_isoline\": 1"));
}
