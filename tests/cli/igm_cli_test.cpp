// Runs the `igm` binary (IGM_CLI_PATH) and checks exit codes and output.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "test_data.h"

namespace {

struct Run {
  int code = -1;
  std::string out, err;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::filesystem::path tmp_dir() {
  const auto d = std::filesystem::temp_directory_path() / ("igm-cli-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d;
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

Run igm(const std::string& args) {
  const auto d = tmp_dir();
  const std::string cmd =
      quote(IGM_CLI_PATH) + " " + args + " >" + quote((d / "out").string()) + " 2>" + quote((d / "err").string());
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(d / "out");
  r.err = slurp(d / "err");
  return r;
}

bool has(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

}  // namespace

// Runs a command line in a fresh working folder; returns it with the run's result.
Run in_folder(const std::filesystem::path& cwd, const std::string& command) {
  std::filesystem::create_directories(cwd);
  const auto d = tmp_dir();
  const std::string cmd = "cd " + quote(cwd.string()) + " && " + command + " >" + quote((d / "stdout").string()) +
                          " 2>" + quote((d / "stderr").string());
  const int status = std::system(cmd.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(d / "stdout");
  r.err = slurp(d / "stderr");
  return r;
}

// A fresh working folder tmp_dir() / name holding the mesh `igm generate ARGS` writes.
std::filesystem::path folder_with_generated(const std::string& name, const std::string& generate_args) {
  const auto cwd = tmp_dir() / name;
  REQUIRE(in_folder(cwd, quote(IGM_CLI_PATH) + " generate " + generate_args).code == 0);
  return cwd;
}

TEST_CASE("igm without arguments runs the pipeline on a generated genus-2 mesh, igm-certify accepts its files") {
  const auto cwd = tmp_dir() / "default-run";
  const Run r = in_folder(cwd, quote(IGM_CLI_PATH));
  CHECK(r.code == 0);
  CHECK(has(r.out, "built-in generated mesh"));
  CHECK(has(r.out, "genus 2"));
  // The default layout is the field one (docs/field.md): its stages, no topological one.
  CHECK(has(r.out, "[field   ]"));
  CHECK(has(r.out, "[trace   ]"));
  CHECK(has(r.out, "[quantize]"));
  CHECK(!has(r.out, "[topology]"));
  CHECK(has(r.out, "[certify ]"));
  CHECK(has(r.out, "certified: VALID"));
  const auto out = cwd / "out";
  for (const char* suffix : {".igm.obj", ".igm.exact", ".quad.obj", ".cert.json", ".schema.svg", ".quad.svg"})
    CHECK(std::filesystem::file_size(out / (std::string("default-genus2") + suffix)) > 0);
  CHECK(has(slurp(out / "default-genus2.quad.svg"), "<svg"));
  // The independent CLI on the written artefacts.
  const Run exact = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " out/default-genus2.igm.exact");
  CHECK(exact.code == 0);
  CHECK(has(exact.out, "\"verdict\": \"valid\""));
  // The doubles file too, as every other tool reads it: its UVs are exactly the certified doubles.
  const Run doubles = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " out/default-genus2.igm.obj");
  CHECK(doubles.code == 0);
  CHECK(has(doubles.out, "\"verdict\": \"valid\""));
  // And `igm extract` on it gives the written quads back (the same count).
  const Run extracted = in_folder(cwd, quote(IGM_CLI_PATH) + " extract out/default-genus2.igm.obj -o re.quad.obj");
  CHECK(extracted.code == 0);
  auto faces = [](const std::string& obj) {
    std::size_t n = 0;
    for (std::size_t at = obj.find("\nf "); at != std::string::npos; at = obj.find("\nf ", at + 1)) ++n;
    return n;
  };
  CHECK(faces(slurp(cwd / "re.quad.obj")) == faces(slurp(out / "default-genus2.quad.obj")));
  const Run quads = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 2 out/default-genus2.quad.obj");
  CHECK(quads.code == 0);
  CHECK(has(slurp(out / "default-genus2.cert.json"), "\"certified\": true"));
  CHECK(has(slurp(out / "default-genus2.cert.json"), "\"layout\": \"field\""));
  CHECK(has(slurp(out / "default-genus2.cert.json"), "\"layout_fallback\": null"));
}

TEST_CASE("igm run: shared torus certified, invalid mesh and bad options exit 2") {
  IGM_REQUIRE_DATA(data);
  const auto cwd = tmp_dir() / "run";
  const std::string igm_cmd = quote(IGM_CLI_PATH);
  const Run ok = in_folder(cwd, igm_cmd + " run " + quote((data / "meshes/clean/pipe.off").string()) +
                                    " -o res --resolution 5 --layout spread");
  CHECK(ok.code == 0);
  CHECK(has(ok.out, "certified: VALID"));
  const Run cert = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 1 res/pipe.quad.obj");
  CHECK(cert.code == 0);
  CHECK(has(cert.out, "\"faces\": 25"));  // one layout quad, 5 x 5
  const Run bad = in_folder(cwd, igm_cmd + " run " + quote((data / "meshes/invalid/b9.ply").string()));
  CHECK(bad.code == 2);
  CHECK(has(bad.err, "no_faces"));
  const std::string pipe = " run " + quote((data / "meshes/clean/pipe.off").string());
  for (const std::string& a : {std::string(" run"), std::string(" run x.off --resolution 1"), std::string(" run x.off --root -3"),
                              std::string(" run x.off --bogus"), pipe + " --resolution 0",
                              pipe + " --cones 1,2,3,4"}) {
    CAPTURE(a);
    CHECK(in_folder(cwd, igm_cmd + a).code == 2);
  }
  // Below the torus's floor (3 along each side of its square: fewer would join its one vertex to
  // itself): raised to it, certified, said.
  const Run floor = in_folder(cwd, igm_cmd + pipe + " -o low --resolution 2 --layout spread");
  CHECK(floor.code == 0);
  CHECK(has(floor.out, "9 quads at resolution 2"));
  CHECK(has(floor.out, "2 chords raised to the floor (9 quads at least)"));
}

TEST_CASE("igm run: a memory limit too small for the arrangement exits 2 in the arrange stage") {
  const auto cwd = folder_with_generated("memory", "--genus 4 --faces 2000 --seed 3 g4.obj");
  const std::string igm_cmd = quote(IGM_CLI_PATH);
  const Run small = in_folder(cwd, igm_cmd + " run g4.obj -o res --memory-limit-mb 1 --layout spread");
  CHECK(small.code == 2);
  CHECK(has(small.err, "unsupported"));
  CHECK(has(small.err, "memory limit"));
  CHECK(has(small.out, "[embed "));
  CHECK(!has(small.out, "[arrange "));  // the overlay stops at the limit
  CHECK(!has(small.out, "[igm "));
  CHECK(!std::filesystem::exists(cwd / "res" / "g4.igm.exact"));
  const Run enough = in_folder(cwd, igm_cmd + " run g4.obj -o res --memory-limit-mb 4096 --layout spread");
  CHECK(enough.code == 0);
  CHECK(has(enough.out, "certified: VALID"));
  for (const char* a : {" run g4.obj --memory-limit-mb 0", " run g4.obj --memory-limit-mb x", " run g4.obj --memory-limit-mb"}) {
    CAPTURE(a);
    CHECK(in_folder(cwd, igm_cmd + a).code == 2);
  }
  std::filesystem::remove_all(cwd);
}

TEST_CASE("igm run --normal-form --restarts: the restarts reach the topology stage, the output certifies") {
  // Generated genus 4 on ~1000 faces: the normal form adds more than 2 % of its 372 vertices.
  const auto cwd = folder_with_generated("restarts", "--genus 4 --faces 1000 --seed 1 g4.obj");
  const std::string igm_cmd = quote(IGM_CLI_PATH);
  const Run r = in_folder(cwd, igm_cmd + " run g4.obj -o res --resolution 3 --normal-form --restarts 2");
  CHECK(r.code == 0);
  CHECK(has(r.out, "of 2 restarts kept"));
  CHECK(has(r.out, "certified: VALID"));
  const Run exact = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " res/g4.igm.exact");
  CHECK(exact.code == 0);
  CHECK(has(exact.out, "\"verdict\": \"valid\""));
  // auto: CutOptions::restarts = -1, clamp(5e6 / (F g^2), 0, 15) = 15 copies on ~1000 faces of genus 4.
  const Run automatic = in_folder(cwd, igm_cmd + " run g4.obj -o auto --resolution 3 --normal-form --restarts auto");
  CHECK(automatic.code == 0);
  CHECK(has(automatic.out, "of 15 restarts kept"));
  CHECK(has(automatic.out, "certified: VALID"));
  const Run plain = in_folder(cwd, igm_cmd + " run g4.obj -o plain --resolution 3 --normal-form");
  CHECK(plain.code == 0);
  CHECK(!has(plain.out, "restarts"));
  for (const char* a : {" run g4.obj --restarts 2", " run g4.obj --normal-form --restarts 65",
                        " run g4.obj --normal-form --restarts -1", " run g4.obj --normal-form --restarts",
                        " run g4.obj --restarts auto", " run g4.obj --normal-form --restarts automatic"}) {
    CAPTURE(a);
    const Run bad = in_folder(cwd, igm_cmd + a);
    CHECK(bad.code == 2);
    CHECK(has(bad.err, "--restarts"));
  }
  std::filesystem::remove_all(cwd);
}

TEST_CASE("help and usage errors") {
  for (const char* a : {"--help", "help", "-h"}) {
    const Run r = igm(a);
    CHECK(r.code == 0);
    CHECK(has(r.out, "usage:"));
    CHECK(has(r.out, "igm info MESH"));
    CHECK(has(r.out, "igm generate --genus G --faces N"));
  }
  for (const char* a : {"run --help", "run -h"}) {  // every option of run, on stdout
    const Run r = igm(a);
    CHECK(r.code == 0);
    CHECK(has(r.out, "usage: igm run MESH"));
    CHECK(has(r.out, "--split-nonmanifold"));
    CHECK(r.err.empty());
  }
  for (const char* a :
       {"--bogus", "bogus", "info", "info a.off b.off", "info --x", "generate", "generate --genus 2 x.obj",
        "generate --genus 2 --faces 100", "generate --genus two --faces 100 x.obj",
        "generate --genus 2 --faces 100 --seed", "generate --genus 2 --faces 100 x.ply",
        "generate --genus 2 --faces 100 --color red x.obj", "help me"}) {
    CAPTURE(a);
    const Run r = igm(a);
    CHECK(r.code == 2);
    CHECK(has(r.err, "usage:"));
    CHECK(r.out.empty());
  }
}

TEST_CASE("generate writes a mesh that info accepts with the requested genus") {
  const auto d = tmp_dir();
  for (int g : {0, 1, 4}) {
    for (const char* ext : {".obj", ".off"}) {
      const std::string out = (d / ("gen" + std::to_string(g) + ext)).string();
      const Run w = igm("generate --genus " + std::to_string(g) + " --faces 500 --seed 7 " + quote(out));
      CHECK(w.code == 0);
      CHECK(has(w.out, "genus " + std::to_string(g)));
      const Run r = igm("info " + quote(out));
      CHECK(r.code == 0);
      CHECK(has(r.out, "genus: " + std::to_string(g) + "\n"));
      CHECK(has(r.out, "boundary loops: 0\n"));
      CHECK(has(r.out, "components: 1\n"));
      CHECK(r.err.empty());
    }
  }
  // Same seed, same file; another seed, another file.
  igm("generate --genus 1 --faces 300 --seed 1 " + quote((d / "a.obj").string()));
  igm("generate --genus 1 --faces 300 --seed 1 " + quote((d / "b.obj").string()));
  igm("generate --genus 1 --faces 300 --seed 2 " + quote((d / "c.obj").string()));
  CHECK(slurp(d / "a.obj") == slurp(d / "b.obj"));
  CHECK(slurp(d / "a.obj") != slurp(d / "c.obj"));
  const Run bad = igm("generate --genus 1 --faces 300 " + quote((d / "no-such-dir" / "x.obj").string()));
  CHECK(bad.code == 2);
  CHECK(has(bad.err, "io"));
  std::filesystem::remove_all(d);
}

TEST_CASE("info on shared meshes: exit codes and the named problems") {
  IGM_REQUIRE_DATA(dir);
  const auto m = dir / "meshes";
  {
    const Run r = igm("info " + quote((m / "clean" / "elephant.off").string()));
    CHECK(r.code == 0);
    CHECK(has(r.out, "vertices: 2775\n"));
    CHECK(has(r.out, "faces: 5558\n"));
    CHECK(has(r.out, "edges: 8337\n"));
    CHECK(has(r.out, "genus: 3\n"));
    CHECK(r.err.empty());
  }
  {
    const Run r = igm("info " + quote((m / "polygonal" / "3torus.off").string()));
    CHECK(r.code == 0);
    CHECK(has(r.out, "genus: 3\n"));
    CHECK(has(r.out, "warning: triangulated 23 polygons"));
  }
  {
    const Run r = igm("info " + quote((m / "repairable" / "cube-shuffled.off").string()));
    CHECK(r.code == 0);
    CHECK(has(r.out, "inconsistently oriented edges: 9\n"));
    CHECK(has(r.out, "warning: re-oriented"));
  }
  {
    const Run r = igm("info " + quote((m / "repairable" / "prim.off").string()));
    CHECK(r.code == 0);
    CHECK(has(r.out, "warning: dropped 3 unreferenced vertices"));
  }
  struct Case {
    const char* file;
    const char* first;
    std::vector<std::string> lines;
    bool surfaces;  // open or several surfaces that `igm run` maps one by one: valid, exit 0
  };
  // Several components and boundary loops are facts (what `igm run` maps), not problems.
  const Case cases[] = {
      {"b9.ply", "no_faces", {"problem: no_faces"}, false},
      {"blobby_3cc.off", "", {"components: 3\n", "boundary loops: 4\n", "genus: 0, 0, 0 (per surface)\n",
                              "surfaces: 3\n"}, true},
      {"degtri_sliding.off", "", {"boundary loops: 1\n", "surfaces: 1\n"}, true},
      {"double-torus-3-holes.off", "", {"boundary loops: 3\n", "genus: 2 (per surface)\n", "surfaces: 1\n"}, true},
      {"knot2.off", "", {"components: 2\n", "genus: 1, 1 (per surface)\n", "surfaces: 2\n"}, true},
      {"pig.stl",
       "non_manifold_vertex",
       {"non-manifold vertices: 421\n", "boundary loops: 5\n", "hint: --split-nonmanifold cuts", "17 surfaces"}, false},
      {"polygon_mesh.off",
       "non_manifold_vertex",
       {"non-manifold vertices: 2\n", "boundary loops: 14\n", "  elements: 4113 4349\n"}, false},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    const Run r = igm("info " + quote((m / "invalid" / c.file).string()));
    for (const std::string& l : c.lines) CHECK(has(r.out, l));
    CHECK_FALSE(has(r.out, "problem: boundary"));
    CHECK_FALSE(has(r.out, "problem: several_components"));
    if (c.surfaces) {
      CHECK(r.code == 0);
      CHECK_FALSE(has(r.out, "problem:"));
      CHECK(has(r.out, "status: valid ("));
    } else {
      CHECK(has(r.out, std::string("problem: ") + c.first));
      CHECK(r.code == 2);
      CHECK(has(r.err, std::string("invalid mesh: ") + c.first));
      CHECK(has(r.out, "status: invalid"));
    }
  }
}

TEST_CASE("info on unreadable files: exit 2 with the reason on stderr") {
  const auto d = tmp_dir();
  {
    const Run r = igm("info " + quote((d / "missing.off").string()));
    CHECK(r.code == 2);
    CHECK(has(r.err, "no such file"));
  }
  {
    std::ofstream(d / "x.txt") << "hello";
    const Run r = igm("info " + quote((d / "x.txt").string()));
    CHECK(r.code == 2);
    CHECK(has(r.err, "unknown mesh file extension"));
  }
  {
    std::ofstream(d / "trunc.off") << "OFF\n4 4 0\n0.0000 0.0000 0.0000\n1.0000 0.0000 0.0000\n0.0000 1.0000 0.0000\n"
                                      "0.0000 0.0000 1.0000\n3 0 1 2\n3 0";
    const Run r = igm("info " + quote((d / "trunc.off").string()));
    CHECK(r.code == 2);
    CHECK(has(r.err, "parse: " + (d / "trunc.off").string() + ": line 8: face 1: expected 3 vertex indices"));
    // So short that the declared counts cannot fit: rejected before reading on.
    std::ofstream(d / "short.off") << "OFF\n4 4 0\n0 0 0\n";
    const Run s = igm("info " + quote((d / "short.off").string()));
    CHECK(s.code == 2);
    CHECK(has(s.err, "too_large: " + (d / "short.off").string() + ": OFF header declares 4 vertices and 4 faces but only"));
  }
  {
    std::ofstream(d / "huge.ply", std::ios::binary)
        << "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
           "property float z\nend_header\n"
        << std::string(100, '\0');
    const Run r = igm("info " + quote((d / "huge.ply").string()));
    CHECK(r.code == 2);
    CHECK(has(r.err, "too_large"));
  }
  {
    std::string garbage;
    for (int i = 0; i < 5000; ++i) garbage += static_cast<char>((i * 7919 + 13) % 256);
    std::ofstream(d / "garbage.stl", std::ios::binary) << garbage;
    const Run r = igm("info " + quote((d / "garbage.stl").string()));
    CHECK(r.code == 2);
    CHECK(has(r.err, "cannot read"));
  }
  std::filesystem::remove_all(d);
}

TEST_CASE("igm run on genus 0: the five files, certified by igm-certify, bad cone lists exit 2") {
  IGM_REQUIRE_DATA(data);
  const auto cwd = tmp_dir() / "run-sphere";
  const std::string igm_cmd = quote(IGM_CLI_PATH);
  const std::string cube = quote((data / "meshes/clean/cube.off").string());
  const Run ok = in_folder(cwd, igm_cmd + " run " + cube + " -o res --resolution 2 --layout spread");
  CHECK(ok.code == 0);
  CHECK(has(ok.out, "genus 0"));
  CHECK(has(ok.out, "certified: VALID"));
  for (const char* suffix : {".igm.obj", ".igm.exact", ".quad.obj", ".cert.json", ".schema.svg"})
    CHECK(std::filesystem::file_size(cwd / "res" / (std::string("cube") + suffix)) > 0);
  const Run exact = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " res/cube.igm.exact");
  CHECK(exact.code == 0);
  CHECK(has(exact.out, "\"cones\": 4"));
  CHECK(has(exact.out, "\"bins\": {\"2\": 4, \"4\": "));  // four vertices of index 2, the rest regular
  const Run quads = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 0 res/cube.quad.obj");
  CHECK(quads.code == 0);
  CHECK(has(quads.out, "\"faces\": 8"));  // 2 N^2
  CHECK(has(quads.out, "\"vertices\": 10"));  // 2 N^2 + 2
  const std::string json = slurp(cwd / "res" / "cube.cert.json");
  CHECK(has(json, "\"certified\": true"));
  CHECK(has(json, "\"genus0\": {\"cones\": ["));
  CHECK(has(slurp(cwd / "res" / "cube.schema.svg"), "<circle"));
  // The default layout (the field one): the cube's corners are its eight cones, of valence 3.
  const Run field = in_folder(cwd, igm_cmd + " run " + cube + " -o resf --quads 600");
  CHECK(field.code == 0);
  CHECK(has(slurp(cwd / "resf" / "cube.cert.json"), "\"layout\": \"field\""));
  const Run field_quads = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 0 resf/cube.quad.obj");
  CHECK(field_quads.code == 0);
  CHECK(has(field_quads.out, "\"bins\": {\"3\": 8, \"4\": "));
  // user cones, in path order, and at resolution 1 (2 quads, 4 vertices of valence 2)
  const Run user = in_folder(cwd, igm_cmd + " run " + cube + " -o res1 --resolution 1 --cones 7,0,3,5");
  CHECK(user.code == 0);
  CHECK(has(user.out, "cones 7 0 3 5"));
  CHECK(has(slurp(cwd / "res1" / "cube.cert.json"), "\"cones\": [7, 0, 3, 5]"));
  const Run q1 = in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 0 res1/cube.quad.obj");
  CHECK(q1.code == 0);
  CHECK(has(q1.out, "\"bins\": {\"2\": 4}"));
  for (const char* cones : {"1,2,3", "1,1,2,3", "0,1,2,8", "0,1,x,3", ""}) {
    CAPTURE(cones);
    const Run bad = in_folder(cwd, igm_cmd + " run " + cube + " --cones '" + cones + "'");
    CHECK(bad.code == 2);
  }
  const Run named = in_folder(cwd, igm_cmd + " run " + cube + " --cones 0,1,2,8");
  CHECK(has(named.err, "entry 3"));
}

TEST_CASE("igm run: layouts, sizes and maps from the command line, the quality report in the certificate and on the terminal") {
  const auto cwd = folder_with_generated("sizes", "--genus 2 --faces 1500 --seed 2 g2.obj");
  const std::string igm_cmd = quote(IGM_CLI_PATH);
  const Run spread = in_folder(cwd, igm_cmd + " run g2.obj -o a --quads 2000 --layout spread");
  CHECK(spread.code == 0);
  CHECK(has(spread.out, "[quality ]"));
  CHECK(has(spread.out, "SJ median"));
  const std::string json = slurp(cwd / "a" / "g2.cert.json");
  CHECK(has(json, "\"quality\": {\"igm\": {"));
  CHECK(has(json, "\"sj_median\""));
  CHECK(has(json, "\"conformal\""));
  CHECK(has(json, "\"layout\": \"spread\""));
  // The quad count is written in the certificate's stats: within a quarter of 2000.
  const auto at = json.find("\"quads\": ");
  REQUIRE(at != std::string::npos);
  const long quads = std::atol(json.c_str() + at + 9);
  CHECK(quads >= 1500);
  CHECK(quads <= 2500);
  const Run kite = in_folder(cwd, igm_cmd + " run g2.obj -o b --layout kite --map affine --edge-length 0.8");
  CHECK(kite.code == 0);
  CHECK(has(slurp(cwd / "b" / "g2.cert.json"), "\"layout\": \"kite\""));
  const Run paper = in_folder(cwd, igm_cmd + " run g2.obj -o c --layout paper --resolution 3");
  CHECK(paper.code == 0);
  CHECK(has(slurp(cwd / "c" / "g2.cert.json"), "\"quads\": 90"));  // 5g N^2
  // Below the paper layout's floor (3 along its sides, which are loops at the root): raised to it,
  // certified, and said.
  const Run floor = in_folder(cwd, igm_cmd + " run g2.obj -o e --layout paper --resolution 2");
  CHECK(floor.code == 0);
  CHECK(has(floor.out, "chords raised to the floor (66 quads at least)"));
  CHECK(has(slurp(cwd / "e" / "g2.cert.json"), "\"raised_by_floor\": true"));
  for (const std::string& a : {std::string(" --layout round"), std::string(" --map conformal"), std::string(" --quads 0"),
                              std::string(" --edge-length -1"), std::string(" --edge-length nan"),
                              std::string(" --quads 10 --resolution 3")}) {
    CAPTURE(a);
    CHECK(in_folder(cwd, igm_cmd + " run g2.obj -o d" + a).code == 2);
  }
}

TEST_CASE("igm run writes the same bytes alone and under load, for any thread count, with the CPU's FMA masked") {
  // ~10k IGM triangles: every parallel loop (chunks of 4,096 elements at most) has several chunks.
  const auto cwd = folder_with_generated("same-bytes", "--genus 3 --faces 6000 --seed 7 g3.obj");
  const std::string run = quote(IGM_CLI_PATH) + " run g3.obj --quads 2000 ";
  // One thread, alone.
  REQUIRE(in_folder(cwd, "(" + run + "-o a --threads 1 > a.log)").code == 0);
  // Two runs at once (each slowed down by the other), with 2 and 3 threads; then one with all
  // cores from IGM_THREADS; then one with glibc told that the CPU has no FMA, AVX or AVX2 (its
  // libm then runs other kernels whose last bits differ: nothing of the output may depend on them).
  REQUIRE(in_folder(cwd, "(" + run + "-o b --threads 2 > b.log & " + run + "-o c --threads 3 > c.log & wait)").code == 0);
  REQUIRE(in_folder(cwd, "(IGM_THREADS=2 " + run + "-o d > d.log)").code == 0);
  REQUIRE(in_folder(cwd, "(GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2_Usable,-FMA_Usable,-AVX_Usable,-AVX2,-FMA,-AVX " + run +
                             "-o e --threads 2 > e.log)").code == 0);
  for (const char* log : {"a.log", "b.log", "c.log", "d.log", "e.log"}) {
    CAPTURE(log);
    CHECK(has(slurp(cwd / log), "certified: VALID"));
    CHECK(has(slurp(cwd / log), "[smooth  ]"));
  }
  for (const char* file : {"g3.igm.obj", "g3.igm.exact", "g3.quad.obj", "g3.quad.svg", "g3.schema.svg"}) {
    CAPTURE(file);
    const std::string a = slurp(cwd / "a" / file);
    CHECK(!a.empty());
    for (const char* other : {"b", "c", "d", "e"}) {
      CAPTURE(other);
      CHECK(slurp(cwd / other / file) == a);
    }
  }
}

TEST_CASE("igm run: features in cert.json and the quality line, --features FILE, bad feature options exit 2") {
  IGM_REQUIRE_DATA(data);
  const auto cwd = tmp_dir() / "features";
  std::filesystem::create_directories(cwd);
  const std::string run = quote(IGM_CLI_PATH) + " run " + quote((data / "meshes/clean/cube.off").string()) + " --quads 300";
  const Run ok = in_folder(cwd, run + " -o res");
  CHECK(ok.code == 0);
  CHECK(has(ok.out, "[features] features 12 curves, 12 edges: "));
  const std::string cert = slurp(cwd / "res/cube.cert.json");
  CHECK(has(cert, "\"features\": {\"edges\": 12, \"curves\": 12, \"corners\": 8, \"short_edges\": 0, \"length\": 24, \"covered_fraction\": "));
  CHECK(in_folder(cwd, quote(IGM_CERTIFY_CLI_PATH) + " --quad --genus 0 res/cube.quad.obj").code == 0);
  const Run info = in_folder(cwd, quote(IGM_CLI_PATH) + " info " + quote((data / "meshes/clean/cube.off").string()));
  CHECK(info.code == 0);
  CHECK(has(info.out, "features: 12 edges, 12 curves, 8 corners"));
  // Only the user's edges: 0 1 is an edge of cube.off (its face 0 is 0 1 3), 0 6 opposite corners.
  std::ofstream(cwd / "f.txt") << "# one crease\n0 1\n";
  const Run user = in_folder(cwd, run + " -o user --no-features --features f.txt");
  CHECK(user.code == 0);
  CHECK(has(user.out, "features 1 curves, 1 edges"));
  for (const auto& [text, said] : {std::pair{"0 1\n0 x\n", "line 2"}, std::pair{"0 6\n", "(0, 6)"}}) {
    std::ofstream(cwd / "bad.txt") << text;
    const Run bad = in_folder(cwd, run + " --features bad.txt");
    CHECK(bad.code == 2);
    CHECK(has(bad.err, said));
  }
  for (const char* a : {" --feature-angle -1", " --feature-angle 181", " --feature-angle x", " --features"}) {
    CAPTURE(a);
    CHECK(in_folder(cwd, run + a).code == 2);
  }
}
