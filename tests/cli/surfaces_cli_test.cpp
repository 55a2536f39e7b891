// `igm generate --boundaries` and `igm info` on meshes with boundaries, several components or
// non-manifold elements (the closed-mesh output is tested in igm_cli_test.cpp).
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "igm/io/read_mesh.h"
#include "igm/mesh/validate_surfaces.h"
#include "test_data.h"

namespace {

namespace fs = std::filesystem;

struct Output {
  int code = -1;
  std::string out, err;
};

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string q(const std::string& s) {  // shell-quoted
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return r + "'";
}

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("igm-surfaces-cli-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// `igm ARGS` with its exit code, stdout and stderr.
Output run_igm(const std::string& args) {
  const fs::path d = scratch();
  const int status = std::system(
      (q(IGM_CLI_PATH) + " " + args + " >" + q((d / "o").string()) + " 2>" + q((d / "e").string()))
          .c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, file_text(d / "o"), file_text(d / "e")};
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

}  // namespace

TEST_CASE("generate --boundaries writes one surface of genus G with B loops, info reports it") {
  const fs::path d = scratch();
  const std::string file = (d / "holes.obj").string();
  const Output w = run_igm("generate --genus 2 --faces 3000 --boundaries 4 --seed 3 " + q(file));
  CHECK(w.code == 0);
  CHECK(has(w.out, "genus 2, 4 boundary loops\n"));
  const igm::SurfaceSet s = igm::validate_surfaces(igm::read_soup(file));
  REQUIRE(s.components.size() == 1);
  CHECK(s.components[0].genus == 2);
  CHECK(s.components[0].boundary_loops.size() == 4);
  const std::string faces = std::to_string(s.components[0].triangles.size());
  const std::string vertices = std::to_string(s.components[0].positions.size());
  CHECK(has(w.out, "wrote " + file + ": " + vertices + " vertices, " + faces + " faces, genus 2"));

  // info: boundary loops are a fact (the surface is what `igm run` maps), not a problem.
  const Output r = run_igm("info " + q(file));
  CHECK(r.code == 0);
  CHECK(has(r.out, "status: valid (1 surface: `igm run` maps each"));
  CHECK(has(r.out, "boundary loops: 4\n"));
  CHECK(has(r.out, "genus: 2 (per surface)\n"));
  CHECK_FALSE(has(r.out, "problem:"));
  CHECK(has(
      r.out,
      "surfaces: 1\nsurface 0: faces " + faces + ", vertices " + vertices +
          ", boundary loops 4, genus 2, euler characteristic -6, first face 0\n"));  // 2 - 4 - 4

  // Too many loops for the size: exit 2 with the capacity.
  const Output big =
      run_igm("generate --genus 0 --faces 100 --boundaries 3 " + q((d / "x.obj").string()));
  CHECK(big.code == 2);
  CHECK(has(big.err, "invalid_argument: 3 boundary loops do not fit"));
  CHECK(has(big.err, "at most 2 well-separated holes"));
  for (const char* bad : {"--boundaries -1", "--boundaries x", "--boundaries"}) {
    CAPTURE(bad);
    const Output u = run_igm(std::string("generate --genus 1 --faces 500 ") + bad + " " +
                             q((d / "y.obj").string()));
    CHECK(u.code == 2);
    CHECK(has(u.err, "usage:"));
  }
  // B = 0 is the closed mesh, byte for byte.
  run_igm("generate --genus 1 --faces 400 --seed 2 " + q((d / "a.off").string()));
  run_igm("generate --genus 1 --faces 400 --seed 2 --boundaries 0 " + q((d / "b.off").string()));
  CHECK(file_text(d / "a.off") == file_text(d / "b.off"));
  CHECK(!file_text(d / "a.off").empty());
  fs::remove_all(d);
}

TEST_CASE("info: a closed valid mesh prints no surface lines, --split-nonmanifold is accepted") {
  const fs::path d = scratch();
  const std::string file = (d / "closed.off").string();
  REQUIRE(run_igm("generate --genus 1 --faces 500 " + q(file)).code == 0);
  for (const char* opt : {"", "--split-nonmanifold "}) {
    CAPTURE(opt);
    const Output r = run_igm(std::string("info ") + opt + q(file));
    CHECK(r.code == 0);
    CHECK(!has(r.out, "surfaces:"));  // (the scratch folder's name has "surfaces" in it)
    CHECK(!has(r.out, "surface 0"));
    CHECK(has(r.out, "status: valid"));
  }
  CHECK(run_igm("info --split " + q(file)).code == 2);
  CHECK(run_igm("info --split-nonmanifold").code == 2);
  fs::remove_all(d);
}

TEST_CASE("info on the shared meshes: surfaces per component, non-manifold ones only when split") {
  IGM_REQUIRE_DATA(dir);
  const fs::path m = dir / "meshes" / "invalid";
  {
    const Output r = run_igm("info " + q((m / "knot2.off").string()));
    CHECK(r.code == 0);  // two closed surfaces: `igm run` maps both
    CHECK(has(r.out, "surfaces: 2\n"));
    CHECK(has(
        r.out,
        "surface 0: faces 5760, vertices 2880, boundary loops 0, genus 1, euler characteristic 0, "
        "first face 0\n"));
    CHECK(has(
        r.out,
        "surface 1: faces 5760, vertices 2880, boundary loops 0, genus 1, euler characteristic 0, "
        "first face 1\n"));
  }
  {
    const Output r = run_igm("info " + q((m / "double-torus-3-holes.off").string()));
    CHECK(has(r.out, "surfaces: 1\n"));
    CHECK(has(r.out, "boundary loops 3, genus 2, euler characteristic -5"));
  }
  {
    const Output r = run_igm("info " + q((m / "blobby_3cc.off").string()));
    CHECK(has(r.out, "surfaces: 3\n"));
    CHECK(has(r.out, "surface 2: "));
  }
  {
    const Output r = run_igm("info " + q((m / "polygon_mesh.off").string()));
    CHECK(r.code == 2);
    CHECK(has(r.out, "problem: non_manifold_vertex (2): 2 vertices"));
    CHECK(has(r.out, "hint: --split-nonmanifold cuts its non-manifold vertices and edges apart: 1 surface (1 of "
                     "genus 4 with 14 boundary loops), all valid input\n"));
    CHECK_FALSE(has(r.out, "problem: boundary"));  // a fact once cut
    const Output s = run_igm("info --split-nonmanifold " + q((m / "polygon_mesh.off").string()));
    CHECK(s.code == 0);  // cut apart, its surfaces are what `igm run --split-nonmanifold` maps
    CHECK(has(s.out, "status: valid (1 surface: `igm run --split-nonmanifold` maps each"));
    CHECK_FALSE(has(s.out, "problem:"));
    CHECK_FALSE(has(s.out, "hint:"));
    CHECK(has(s.out, "non-manifold vertices: 2\n"));
    // 16,344 vertices + 3 copies - 48,612 edges + 32,245 faces = -20 = 2 - 2 * 4 - 14
    CHECK(has(s.out,
              "surfaces: 1\nsurface 0: faces 32245, vertices 16347, boundary loops 14, genus 4, "
              "euler characteristic -20, first face 0\n"));
    CHECK(has(
        s.out,
        "surfaces warning: cut 2 non-manifold vertices into one copy per fan (5 vertices in all): "
        "vertex 4113 (3 fans); vertex 4349 (2 fans)\n"));
  }
  {
    const Output r = run_igm("info --split-nonmanifold " + q((m / "pig.stl").string()));
    CHECK(has(r.out, "surfaces: 17\n"));  // 17 edge-connected face sets (counted apart, in Python)
    CHECK(has(r.out, "surfaces warning: cut 421 non-manifold vertices"));
  }
  {
    const Output r = run_igm("info --split-nonmanifold " + q((m / "b9.ply").string()));
    CHECK(r.code == 2);
    CHECK(!has(r.out, "surfaces:"));
    CHECK(has(r.out, "problem: no_faces"));
  }
}

namespace {

// `igm-certify ARGS`: its exit code.
int run_certify(const std::string& args) {
  return WEXITSTATUS(std::system((q(IGM_CERTIFY_CLI_PATH) + " " + args + " >/dev/null 2>&1").c_str()));
}

}  // namespace

TEST_CASE("run on an open mesh: certified outputs whose files igm-certify accepts in boundary mode only") {
  const fs::path d = scratch();
  const std::string mesh = (d / "holes.obj").string();
  REQUIRE(run_igm("generate --genus 1 --boundaries 3 --faces 1500 " + q(mesh)).code == 0);
  const Output r = run_igm("run " + q(mesh) + " -o " + q((d / "out").string()) + " --quads 800 --smooth-iterations 5");
  CHECK(r.code == 0);
  CHECK(has(r.out, "genus 1, 3 boundary loops"));
  const std::string cert = file_text(d / "out" / "holes.cert.json");
  CHECK(has(cert, "\"certified\": true"));
  CHECK(has(cert, "\"boundary_loops\": 3"));
  const std::string igm = q((d / "out" / "holes.igm.obj").string()), exact = q((d / "out" / "holes.igm.exact").string());
  const std::string quads = q((d / "out" / "holes.quad.obj").string());
  CHECK(run_certify("--boundary " + igm) == 0);
  CHECK(run_certify("--boundary " + exact) == 0);
  CHECK(run_certify("--quad --boundary --genus 1 --boundary-loops 3 " + quads) == 0);
  CHECK(run_certify(igm) == 1);                                                     // boundary edges need --boundary
  CHECK(run_certify("--quad --boundary --genus 1 --boundary-loops 2 " + quads) == 1);  // the loops are counted
  CHECK(fs::file_size(d / "out" / "holes.quad.svg") > 0);
  // extraction from the written IGM gives the same number of quads
  const Output x = run_igm("extract " + igm + " --boundary -o " + q((d / "x.obj").string()));
  CHECK(x.code == 0);
  const igm::SurfaceSet a = igm::validate_surfaces(igm::read_soup(d / "x.obj"));
  const igm::SurfaceSet b = igm::validate_surfaces(igm::read_soup(d / "out" / "holes.quad.obj"));
  REQUIRE(a.components.size() == 1);
  REQUIRE(b.components.size() == 1);
  CHECK(a.components[0].triangles.size() == b.components[0].triangles.size());  // two per quad
  CHECK(a.components[0].boundary_loops.size() == 3);
  fs::remove_all(d);
}

TEST_CASE("run on shared meshes with several components and non-manifold elements") {
  IGM_REQUIRE_DATA(dir);
  const fs::path d = scratch();
  const fs::path m = dir / "meshes" / "invalid";
  {
    const Output r = run_igm("run " + q((m / "knot2.off").string()) + " -o " + q((d / "k").string()) +
                             " --quads 1500 --smooth-iterations 3");
    CHECK(r.code == 0);
    const std::string cert = file_text(d / "k" / "knot2.cert.json");
    CHECK(has(cert, "\"surfaces\": 2}"));
    CHECK(has(cert, "\"certified\": true"));
    CHECK(run_certify("--components " + q((d / "k" / "knot2.igm.obj").string())) == 0);
    CHECK(run_certify("--quad --components --component 1:0 --component 1:0 " + q((d / "k" / "knot2.quad.obj").string())) == 0);
    CHECK(run_certify(q((d / "k" / "knot2.igm.obj").string())) == 1);  // two components need --components
  }
  {
    const std::string pig = q((m / "pig.stl").string());
    CHECK(run_igm("run " + pig + " -o " + q((d / "p").string())).code == 2);  // non-manifold: typed error
    const Output r = run_igm("run --split-nonmanifold " + pig + " -o " + q((d / "p").string()) + " --quads 1500 --no-smooth");
    CHECK(r.code == 0);
    CHECK(has(r.err + r.out, "cut 421 non-manifold vertices"));
    CHECK(has(file_text(d / "p" / "pig.cert.json"), "\"surfaces\": 17}"));
  }
  fs::remove_all(d);
}

TEST_CASE("run and info on a non-manifold mesh name --split-nonmanifold, and what would still be wrong") {
  const fs::path d = scratch();
  // Two tetrahedra sharing vertex 0 (a bow tie of spheres): cut apart, two closed surfaces.
  const std::string bow = (d / "bow.obj").string();
  write_text(bow,
             "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv -1 0 0\nv 0 -1 0\nv 0 0 -1\n"
             "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 5 6\nf 1 7 5\nf 1 6 7\nf 5 7 6\n");
  const Output r = run_igm("run " + q(bow) + " -o " + q((d / "mapped").string()));
  CHECK(r.code == 2);
  CHECK(has(r.err, "non_manifold_vertex: 1 vertex has faces forming more than one fan: vertex 0 (2 fans); "
                   "--split-nonmanifold cuts its non-manifold vertices and edges apart: 2 surfaces"));
  const Output i = run_igm("info " + q(bow));
  CHECK(i.code == 2);
  CHECK(has(i.out, "hint: --split-nonmanifold cuts its non-manifold vertices and edges apart: 2 surfaces"));
  const Output s = run_igm("run --split-nonmanifold " + q(bow) + " -o " + q((d / "mapped").string()));
  CHECK(s.code == 0);
  // A Moebius strip touching a triangle at vertex 0: cutting leaves a non-orientable surface.
  const std::string moebius = (d / "moebius.obj").string();
  write_text(moebius,
             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\nv -1 0 0\nv -1 -1 0\n"
             "f 1 2 3\nf 2 3 4\nf 3 4 5\nf 4 5 1\nf 5 1 2\nf 1 6 7\n");
  const Output m = run_igm("run " + q(moebius) + " -o " + q((d / "mapped").string()));
  CHECK(m.code == 2);
  CHECK(has(m.err, "--split-nonmanifold would cut its non-manifold vertices and edges apart, but then: non_orientable"));
  const Output mi = run_igm("info " + q(moebius));
  CHECK(has(mi.out, "hint: --split-nonmanifold would cut its non-manifold vertices and edges apart, but then: "
                    "non_orientable"));
  fs::remove_all(d);
}
