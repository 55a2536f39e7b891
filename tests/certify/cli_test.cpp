// igm-certify CLI: exit codes 0/1/2 and the JSON it writes.
#include <doctest/doctest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "igm_builders.h"

namespace fs = std::filesystem;
using namespace certify_test;

namespace {

fs::path tmp_dir() {
  fs::path d = fs::temp_directory_path() / ("igm_certify_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) {
  std::ofstream o(p, std::ios::binary);
  o << text;
}

std::string slurp(const fs::path& p) {
  std::ifstream i(p, std::ios::binary);
  std::stringstream s;
  s << i.rdbuf();
  return s.str();
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
