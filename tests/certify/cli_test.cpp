// igm-certify CLI: exit codes 0/1/2 and the JSON it writes.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "boundary_builders.h"
#include "cli_files.h"

namespace fs = std::filesystem;
using namespace certify_test;

namespace {

fs::path tmp_dir() {
  fs::path d = fs::temp_directory_path() / ("igm_certify_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Runs the CLI with args; returns the exit code, stdout in out.
int run(const std::string& args, std::string& out, const fs::path& dir) {
  const fs::path o = dir / "stdout.txt", e = dir / "stderr.txt";
  const std::string cmd = std::string("\"") + IGM_CERTIFY_CLI_PATH + "\" " + args + " > \"" + o.string() +
                          "\" 2> \"" + e.string() + "\"";
  const int st = std::system(cmd.c_str());
  out = slurp(o);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

}  // namespace

TEST_CASE("cli: exit codes and JSON") {
  const fs::path dir = tmp_dir();
  std::string out;

  write(dir / "valid.obj", to_obj(cube(2)));
  CHECK(run("\"" + (dir / "valid.obj").string() + "\"", out, dir) == 0);
  CHECK(out.find("\"verdict\": \"valid\"") != std::string::npos);
  CHECK(out.find("\"exit_code\": 0") != std::string::npos);
  CHECK(out.find("\"genus\": 0") != std::string::npos);
  CHECK(slurp(dir / "stderr.txt").find("VALID") != std::string::npos);

  // the same IGM written with decimals is valid too
  write(dir / "valid_dec.obj", to_obj(pillow(2), true));
  CHECK(run("\"" + (dir / "valid_dec.obj").string() + "\"", out, dir) == 0);

  IgmInput flipped = torus(4);
  std::swap(flipped.corner_uv[1], flipped.corner_uv[2]);
  write(dir / "invalid.obj", to_obj(flipped));
  CHECK(run("--max-witnesses 1 \"" + (dir / "invalid.obj").string() + "\"", out, dir) == 1);
  CHECK(out.find("\"verdict\": \"invalid\"") != std::string::npos);
  CHECK(out.find("\"kind\": \"face\", \"ids\": [0]") != std::string::npos);
  CHECK(out.find("\"witnesses_shown\": 1") != std::string::npos);

  // --json writes the file, stdout stays empty
  CHECK(run("--json \"" + (dir / "cert.json").string() + "\" \"" + (dir / "invalid.obj").string() + "\"", out, dir) == 1);
  CHECK(out.empty());
  CHECK(slurp(dir / "cert.json").find("\"verdict\": \"invalid\"") != std::string::npos);

  write(dir / "garbage.obj", "v 1 2 3\nvt 0.5 nan\n");
  CHECK(run("\"" + (dir / "garbage.obj").string() + "\"", out, dir) == 2);
  CHECK(out.find("\"verdict\": \"unreadable\"") != std::string::npos);
  CHECK(out.find("\"line\": 2") != std::string::npos);

  CHECK(run("\"" + (dir / "missing.obj").string() + "\"", out, dir) == 2);
  CHECK(run("", out, dir) == 2);
  CHECK(run("--bogus x", out, dir) == 2);
  CHECK(run("--max-witnesses", out, dir) == 2);

  // quad mode
  write(dir / "cube_quads.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
        "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n");
  CHECK(run("--quad \"" + (dir / "cube_quads.obj").string() + "\"", out, dir) == 0);
  CHECK(out.find("\"mode\": \"quad\"") != std::string::npos);
  CHECK(run("--quad --genus 0 \"" + (dir / "cube_quads.obj").string() + "\"", out, dir) == 0);
  CHECK(run("--quad --genus 2 \"" + (dir / "cube_quads.obj").string() + "\"", out, dir) == 1);
  // a quad mesh is not an IGM
  CHECK(run("\"" + (dir / "cube_quads.obj").string() + "\"", out, dir) == 2);

  fs::remove_all(dir);
}

TEST_CASE("cli: --boundary, --components, --boundary-loops, --component") {
  const fs::path dir = tmp_dir();
  std::string out;
  auto file = [&](const char* name) { return " \"" + (dir / name).string() + "\""; };

  write(dir / "disk.obj", to_obj(square_disk(3).igm));
  CHECK(run(file("disk.obj"), out, dir) == 1);  // the old behaviour: a boundary fails check 1
  CHECK(out.find("\"reason\": \"boundary edge (one face)\"") != std::string::npos);
  CHECK(run("--boundary" + file("disk.obj"), out, dir) == 0);
  CHECK(out.find("\"boundary_loops\": 1, \"connected_components\": 1}") != std::string::npos);
  CHECK(out.find("\"boundary_index_k\", \"bins\": {\"1\": 4, \"2\": 8}") != std::string::npos);
  CHECK(slurp(dir / "stderr.txt").find("boundary_loops=1") != std::string::npos);

  GridPatch off = square_disk(3);
  move_vertex(off.igm, off.id(1, 0), uv(1, mpq_class(1, 1000)));
  write(dir / "off.obj", to_obj(off.igm));
  CHECK(run("--boundary" + file("off.obj"), out, dir) == 1);
  CHECK(out.find("boundary edge not on an integer isoline") != std::string::npos);

  write(dir / "two.obj", to_obj(disjoint_union(torus(3), cube(1))));
  CHECK(run(file("two.obj"), out, dir) == 1);
  CHECK(run("--components" + file("two.obj"), out, dir) == 0);
  CHECK(out.find("\"first_vertex\": 9") != std::string::npos);

  // quad mode: a 3 x 3 grid disk, then the same grid with its centre punched out
  write(dir / "grid.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nv 0 2 0\nv 1 2 0\nv 2 2 0\n"
        "f 1 2 5 4\nf 2 3 6 5\nf 4 5 8 7\nf 5 6 9 8\n");
  CHECK(run("--quad" + file("grid.obj"), out, dir) == 1);
  CHECK(run("--quad --boundary" + file("grid.obj"), out, dir) == 0);
  CHECK(run("--quad --boundary --boundary-loops 1 --genus 0" + file("grid.obj"), out, dir) == 0);
  CHECK(run("--quad --boundary --boundary-loops 2" + file("grid.obj"), out, dir) == 1);
  CHECK(out.find("number of boundary loops differs from the expected one") != std::string::npos);
  CHECK(run("--quad --boundary --component 0:1" + file("grid.obj"), out, dir) == 0);
  CHECK(run("--quad --boundary --component 1:1" + file("grid.obj"), out, dir) == 1);
  std::string holed = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\n";
  for (int j = 1; j <= 3; ++j)
    for (int i = 0; i <= 3; ++i)
      holed += "v " + std::to_string(i) + " " + std::to_string(j) + " 0\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      if (i == 1 && j == 1) continue;
      const int a = 1 + i + 4 * j;
      holed += "f " + std::to_string(a) + " " + std::to_string(a + 1) + " " +
               std::to_string(a + 5) + " " + std::to_string(a + 4) + "\n";
    }
  write(dir / "holed.obj", holed);
  CHECK(run("--quad --boundary --boundary-loops 2" + file("holed.obj"), out, dir) == 0);
  CHECK(run("--quad --boundary --boundary-loops 1" + file("holed.obj"), out, dir) == 1);

  // bad arguments
  CHECK(run("--boundary-loops 1" + file("disk.obj"), out, dir) == 2);          // needs --quad
  CHECK(run("--quad --boundary-loops 1" + file("grid.obj"), out, dir) == 2);   // needs --boundary
  CHECK(run("--quad --boundary --boundary-loops -1" + file("grid.obj"), out, dir) == 2);
  CHECK(run("--quad --boundary --component 0" + file("grid.obj"), out, dir) == 2);
  CHECK(run("--quad --boundary --component 0:x" + file("grid.obj"), out, dir) == 2);
  CHECK(run("--quad --boundary --component 0:1 --component 0:1" + file("grid.obj"), out, dir) == 2);
  const std::string twice = "--quad --boundary --components --component 0:1 --component 0:1";
  CHECK(run(twice + file("grid.obj"), out, dir) == 1);

  fs::remove_all(dir);
}
