// Runs `igm extract` (IGM_CLI_PATH) on IGM files: exit codes, the quad OBJ (checked by
// igm-certify, IGM_CERTIFY_CLI_PATH), the JSON report, the certifier's witnesses.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../certify/boundary_builders.h"
#include "test_data.h"

namespace {

struct ExtractRun {
  int code = -1;
  std::string out, err;
};

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// A fresh folder for one test case, removed with everything in it at the end of the case.
struct Folder {
  std::filesystem::path path;
  explicit Folder(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("igm-extract-cli-" + std::to_string(::getpid()) + "-" + name)) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~Folder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  Folder(const Folder&) = delete;
  Folder& operator=(const Folder&) = delete;
  operator const std::filesystem::path&() const { return path; }
  std::filesystem::path operator/(const std::string& file) const { return path / file; }
};

// Runs `BINARY ARGS` in folder `cwd`.
ExtractRun run_in(const std::filesystem::path& cwd, const std::string& binary,
                  const std::string& args) {
  const std::string cmd = "cd " + shell_quote(cwd.string()) + " && " + shell_quote(binary) + " " +
                          args + " >" + shell_quote((cwd / "stdout.txt").string()) + " 2>" +
                          shell_quote((cwd / "stderr.txt").string());
  const int status = std::system(cmd.c_str());
  ExtractRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(cwd / "stdout.txt");
  r.err = read_text(cwd / "stderr.txt");
  return r;
}

ExtractRun extract(const std::filesystem::path& cwd, const std::string& args) {
  return run_in(cwd, IGM_CLI_PATH, "extract " + args);
}

// Writes `igm` as OBJ text (exact p/q UVs, or decimals) to dir/file, then `igm extract file
// OPTIONS`.
ExtractRun extract_igm(const std::filesystem::path& dir, const std::string& file,
                       const igm::certify::IgmInput& igm, const std::string& options,
                       bool decimal = false) {
  write_text(dir / file, certify_test::to_obj(igm, decimal));
  return extract(dir, file + " " + options);
}

bool contains(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

// Counts the lines of an OBJ starting with `key `, and checks that every `f` line has 4 indices.
int count_lines(const std::string& obj, const std::string& key, bool* all_quads = nullptr) {
  std::istringstream in(obj);
  std::string line;
  int n = 0;
  if (all_quads) *all_quads = true;
  while (std::getline(in, line)) {
    if (line.rfind(key + " ", 0) != 0) continue;
    ++n;
    if (all_quads && key == "f") {
      std::istringstream l(line.substr(2));
      int a = 0, k = 0;
      while (l >> a) ++k;
      if (k != 4) *all_quads = false;
    }
  }
  return n;
}

}  // namespace

TEST_CASE(
    "igm extract: a 4 x 4 torus IGM (exact p/q UVs) gives 16 certified quads, the OBJ and the "
    "JSON") {
  const Folder dir("torus");
  const ExtractRun r = extract_igm(dir, "torus.igm.exact", certify_test::torus(4),
                                   "-o quads.obj --json report.json");
  CHECK(r.code == 0);
  CHECK(contains(
      r.out, "16 quads, 16 vertices (16 on mesh vertices, 0 on edges, 0 in triangles; 0 cones)"));
  CHECK(contains(r.out, "genus 1"));
  CHECK(contains(r.out, "certified"));
  const std::string obj = read_text(dir / "quads.obj");
  bool quads = false;
  CHECK(count_lines(obj, "f", &quads) == 16);
  CHECK(quads);
  CHECK(count_lines(obj, "v") == 16);
  CHECK(
      contains(obj, "v 15 0 0"));  // the builder's vertex 15 sits at (15, 0, 0): a grid point on it
  CHECK(run_in(dir, IGM_CERTIFY_CLI_PATH, "--quad --genus 1 quads.obj").code == 0);
  const std::string json = read_text(dir / "report.json");
  CHECK(contains(json, "\"exit_code\": 0"));
  CHECK(contains(json, "\"quads\": 16"));
  CHECK(contains(json, "\"verdict\": \"valid\""));
  CHECK(contains(json, "\"mode\": \"quad\""));
}

TEST_CASE("igm extract: decimal UVs, grid points inside triangles, the default output name") {
  const Folder dir("decimal");
  igm::certify::IgmInput torus = certify_test::torus(3);
  certify_test::map_faces(torus, certify_test::block_faces(3, 0, 3, 0, 3), 1, 0, 0, 1,
                          mpq_class(1, 4), mpq_class(1, 2));
  const ExtractRun r = extract_igm(dir, "shifted.igm.obj", torus, "", true);
  REQUIRE(contains(read_text(dir / "shifted.igm.obj"), "vt 0.250000000000 0.500000000000"));
  CHECK(r.code == 0);
  CHECK(contains(r.out,
                 "9 quads, 9 vertices (0 on mesh vertices, 0 on edges, 9 in triangles; 0 cones)"));
  CHECK(std::filesystem::exists(dir / "shifted.quad.obj"));
  CHECK(run_in(dir, IGM_CERTIFY_CLI_PATH, "--quad --genus 1 shifted.quad.obj").code == 0);
}

TEST_CASE(
    "igm extract: cones (the cube's corners) and a coarse grid with multiple edges (exit 1, "
    "written anyway)") {
  const Folder dir("cones");
  const ExtractRun cube = extract_igm(dir, "cube.obj", certify_test::cube(2), "-o cube.quad.obj");
  CHECK(cube.code == 0);
  CHECK(contains(
      cube.out,
      "24 quads, 26 vertices (26 on mesh vertices, 0 on edges, 0 in triangles; 8 cones), genus 0"));
  // The 4 x 4 torus scaled by 1/2: 4 quads on 4 vertices, each pair joined by two edges, which
  // certifier check 5 (edges by their end points) refuses.
  igm::certify::IgmInput half = certify_test::torus(4);
  for (auto& uv : half.corner_uv) uv = {uv[0] / 2, uv[1] / 2};
  const ExtractRun small =
      extract_igm(dir, "small.obj", half, "-o small.quad.obj --json small.json");
  CHECK(small.code == 1);
  CHECK(contains(small.out, "4 quads, 4 vertices"));
  CHECK(contains(small.out, "NOT CERTIFIED"));
  // ... and says why: the double edges, named.
  CHECK(contains(small.out, "the integer isolines are no manifold quad mesh"));
  CHECK(contains(small.out, "2 edges ("));
  CHECK(contains(small.out, "more quads separate them"));
  CHECK(std::filesystem::exists(dir / "small.quad.obj"));
  CHECK(contains(read_text(dir / "small.json"), "\"exit_code\": 1"));
  CHECK(contains(read_text(dir / "small.json"), "\"quad_defects\": \"the integer isolines"));
  // The genus-0 pillow of 2 x 1 quads a side (issue 47's 4 quads on 6 vertices): the double edge
  // lies in the quads of all four cones.
  igm::certify::IgmInput pillow = certify_test::pillow(2);
  for (auto& uv : pillow.corner_uv) uv = {uv[0], uv[1] / 2};
  const ExtractRun flat = extract_igm(dir, "pillow.obj", pillow, "-o pillow.quad.obj");
  CHECK(flat.code == 1);
  CHECK(contains(flat.out, "4 quads, 6 vertices"));
  CHECK(contains(flat.out, "2 edges ("));
  CHECK(contains(flat.out, "which share the cones"));
}

TEST_CASE(
    "igm extract: a nudged corner UV is refused: exit 1, the certifier's witness printed and in "
    "the JSON") {
  const Folder dir("nudged");
  igm::certify::IgmInput torus = certify_test::torus(4);
  torus.corner_uv[3 * 5 + 1][0] += mpq_class(1, 1000);  // face 5's corner at vertex 7
  const ExtractRun r =
      extract_igm(dir, "nudged.obj", torus, "-o nudged.quad.obj --json nudged.json");
  CHECK(r.code == 1);
  CHECK(contains(r.out, "NOT AN IGM"));
  CHECK(contains(r.out, "edge 2 7: edge vectors not related by a rotation R^k"));
  CHECK_FALSE(std::filesystem::exists(dir / "nudged.quad.obj"));
  const std::string json = read_text(dir / "nudged.json");
  CHECK(contains(json, "\"extraction\": null"));
  CHECK(contains(json, "\"verdict\": \"invalid\""));
  CHECK(contains(json, "\"ids\": [2, 7]"));
}

TEST_CASE("igm extract: the shared third-party IGMs are invalid: exit 1") {
  IGM_REQUIRE_DATA(data);
  const Folder dir("shared");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(data / "igm")) {
    if (e.path().extension() != ".obj") continue;
    ++files;
    CAPTURE(e.path().string());
    const ExtractRun r = extract(dir, shell_quote(e.path().string()) + " --json r.json");
    CHECK(r.code == 1);
    CHECK(contains(r.out, "NOT AN IGM"));
    CHECK(contains(r.out, "check 3 transitions: fail"));
    CHECK(contains(read_text(dir / "r.json"), "\"valid\": false"));
  }
  CHECK(files == 3);
}

TEST_CASE("igm extract: unreadable files and usage errors exit 2") {
  const Folder dir("unreadable");
  write_text(dir / "garbage.obj", "v 0 0 0\nthis is not obj\n");
  write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\n");
  write_text(dir / "nouv.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  const ExtractRun garbage = extract(dir, "garbage.obj --json g.json");
  CHECK(garbage.code == 2);
  CHECK(contains(garbage.err, "line 2"));
  CHECK(contains(read_text(dir / "g.json"), "\"verdict\": \"unreadable\""));
  const ExtractRun quad = extract(dir, "quad.obj");
  CHECK(quad.code == 2);
  CHECK(contains(quad.err, "face with 4 corners"));
  CHECK(extract(dir, "nouv.obj").code == 2);
  CHECK(extract(dir, "missing.obj").code == 2);
  CHECK(extract(dir, "").code == 2);
  CHECK(extract(dir, "a.obj b.obj").code == 2);
  CHECK(extract(dir, "garbage.obj --frobnicate").code == 2);
  CHECK(extract(dir, "garbage.obj -o").code == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "garbage.quad.obj"));
}

TEST_CASE(
    "igm extract --boundary --components: an L-shape and a torus, certified with their loops; "
    "refused without the flags, with a hint") {
  const Folder dir("open");
  // [0, 4]^2 without its upper right quarter (12 quads) and the 3 x 3 torus (9 quads).
  const igm::certify::IgmInput both =
      certify_test::disjoint_union(certify_test::l_shape(2).igm, certify_test::torus(3));
  const ExtractRun r = extract_igm(dir, "both.obj", both,
                                   "--boundary --components -o both.quad.obj --json both.json");
  CHECK(r.code == 0);
  CHECK(contains(r.out, "21 quads, 30 vertices"));
  CHECK(contains(r.out, "genus 1, 1 boundary loops"));
  CHECK(contains(r.out, "certified"));
  CHECK(run_in(dir, IGM_CERTIFY_CLI_PATH,
               "--quad --boundary --components --component 0:1 --component 1:0 both.quad.obj")
            .code == 0);
  const std::string json = read_text(dir / "both.json");
  CHECK(contains(json, "\"boundary_loops\": 1"));
  CHECK(contains(json, "\"grid_points_on_boundary\": 16"));
  CHECK(contains(json, "\"boundary_corners\": 6"));
  const ExtractRun closed = extract_igm(dir, "both.obj", both, "-o refused.quad.obj");
  CHECK(closed.code == 1);
  CHECK(contains(closed.out, "NOT AN IGM"));
  CHECK(contains(closed.out, "--boundary accepts them"));
  CHECK(contains(closed.out, "--components accepts them"));
  CHECK_FALSE(std::filesystem::exists(dir / "refused.quad.obj"));
}
