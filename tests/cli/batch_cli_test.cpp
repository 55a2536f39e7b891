// `igm batch` (src/cli/batch_command.cpp): verdicts and the summary over a folder, resuming
// after a kill, the time and memory limits, and GNU parallel runs sharing one results file.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "test_data.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;

struct Proc {
  int code = -1;  // exit code, -1 when killed by a signal
  std::string out, err;
};

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Starts argv[0] (searched in PATH) in `cwd`, stdout and stderr to cwd/NAME.out and .err.
pid_t launch(const fs::path& cwd, const std::vector<std::string>& argv, const std::string& name) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (cwd / (name + ".out")).c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (cwd / (name + ".err")).c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  REQUIRE(rc == 0);
  return pid;
}

Proc finish(const fs::path& cwd, pid_t pid, const std::string& name) {
  int status = 0;
  waitpid(pid, &status, 0);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, contents(cwd / (name + ".out")),
          contents(cwd / (name + ".err"))};
}

// `igm ARGS` in cwd, waited for.
Proc igm(const fs::path& cwd, std::vector<std::string> args) {
  args.insert(args.begin(), IGM_CLI_PATH);
  return finish(cwd, launch(cwd, args, "cmd"), "cmd");
}

// A fresh folder for one test case.
fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("igm-batch-test-" + std::to_string(getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void generate(const fs::path& cwd, const std::string& genus, const std::string& faces, const std::string& seed,
              const std::string& out) {
  REQUIRE(igm(cwd, {"generate", "--genus", genus, "--faces", faces, "--seed", seed, out}).code == 0);
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) lines.push_back(l);
  return lines;
}

// The string value of "key" in a results line ("" when absent).
std::string field(const std::string& line, const std::string& key) {
  const std::string tag = "\"" + key + "\": \"";
  const auto at = line.find(tag);
  if (at == std::string::npos) return "";
  const auto b = at + tag.size();
  return line.substr(b, line.find('"', b) - b);
}

// verdict per file name (the path's last part) of OUT/results.jsonl; fails on a file seen twice.
std::map<std::string, std::string> verdicts(const fs::path& out) {
  std::map<std::string, std::string> v;
  for (const std::string& l : lines_of(contents(out / "results.jsonl"))) {
    const std::string name = fs::path(field(l, "file")).filename().string();
    CHECK_MESSAGE(!v.count(name), "twice: " << name);
    v[name] = field(l, "verdict");
  }
  return v;
}

// The count the summary prints for a verdict ("  certified      6").
int summary_count(const std::string& summary, const std::string& verdict) {
  const std::regex row("\\n  " + verdict + " +([0-9]+)\\n");
  std::smatch m;
  if (!std::regex_search(summary, m, row)) return -1;
  return std::stoi(m[1]);
}

bool has(const std::string& text, const std::string& needle) { return text.find(needle) != std::string::npos; }

}  // namespace

TEST_CASE("igm batch over a folder: a verdict per mesh, the summary's counts, --summary") {
  IGM_REQUIRE_DATA(data);
  const fs::path cwd = scratch("folder");
  const fs::path in = cwd / "in";
  fs::create_directories(in / "sub");
  generate(cwd, "1", "300", "1", "in/g1.obj");
  generate(cwd, "2", "400", "2", "in/sub/g2.off");  // found in a subfolder
  const fs::path meshes = data / "meshes";
  for (const char* m : {"clean/tetrahedron.off", "clean/pipe.off", "polygonal/hole.off", "repairable/cube-shuffled.off",
                        "invalid/b9.ply", "invalid/knot2.off", "invalid/polygon_mesh.off"})
    fs::copy_file(meshes / m, in / fs::path(m).filename());
  std::ofstream(in / "notes.txt") << "not a mesh\n";

  const Proc r = igm(cwd, {"batch", "in", "-o", "out", "-j", "2"});
  INFO(r.err);
  CHECK(r.code == 0);
  const std::map<std::string, std::string> expected = {
      {"g1.obj", "certified"},        {"g2.off", "certified"},          {"tetrahedron.off", "certified"},
      {"pipe.off", "certified"},      {"hole.off", "certified"},        {"cube-shuffled.off", "certified"},
      {"b9.ply", "invalid_input"},    {"knot2.off", "certified"},       {"polygon_mesh.off", "invalid_input"}};
  CHECK(verdicts(cwd / "out") == expected);
  for (const std::string& l : lines_of(contents(cwd / "out/results.jsonl"))) {
    CAPTURE(l);
    CHECK(field(l, "file").front() == '/');  // absolute
    CHECK(has(l, "\"seconds\": "));
    CHECK(has(l, "\"peak_mb\": "));
    if (has(l, "b9.ply")) CHECK(field(l, "error_kind") == "no_faces");
    if (has(l, "polygon_mesh.off")) CHECK(field(l, "error_kind") == "non_manifold_vertex");  // without --split-nonmanifold
    if (field(l, "verdict") == "certified") {
      CHECK(!has(l, "error_kind"));
      CHECK(has(l, "\"quads\": "));
      CHECK(has(l, "\"raised_by_floor\": false"));  // 10,000 quads: above every floor here
      const fs::path stem = fs::path(field(l, "file")).stem();
      CHECK(fs::file_size(cwd / "out/runs" / field(l, "id") / (stem.string() + ".quad.obj")) > 0);
    }
  }
  CHECK(summary_count(r.out, "certified") == 7);
  CHECK(summary_count(r.out, "invalid_input") == 2);
  CHECK(summary_count(r.out, "timeout") == 0);
  CHECK(has(r.out, "(9 meshes)"));  // the time quantiles
  const Proc s = igm(cwd, {"batch", "--summary", "-o", "out"});
  CHECK(s.code == 0);
  CHECK(summary_count(s.out, "certified") == 7);
  CHECK(summary_count(s.out, "invalid_input") == 2);
  // OUT inside DIR: the runs' own .obj outputs are not taken for meshes of the job.
  fs::rename(cwd / "out", in / "out");  // its lines name the meshes by their absolute paths still
  const Proc inner = igm(cwd, {"batch", "in", "-o", "in/out"});
  CHECK(inner.code == 0);
  CHECK(has(inner.err, "[batch] 9 meshes, 9 done already, 0 to run"));
  // The floor in a batch: the tetrahedron asked 1 quad gets the 2 of its 1 x 1 pillowcase, said.
  const Proc floor = igm(cwd, {"batch", "in/tetrahedron.off", "-o", "floor", "--", "--quads", "1", "--layout", "spread"});
  CHECK(floor.code == 0);
  CHECK(has(contents(cwd / "floor/results.jsonl"), "\"verdict\": \"certified\""));
  CHECK(has(contents(cwd / "floor/results.jsonl"), "\"quads\": 2, \"raised_by_floor\": true"));
  fs::remove_all(cwd);
}

TEST_CASE("igm batch killed after the first mesh and resumed runs each mesh once") {
  const fs::path cwd = scratch("resume");
  fs::create_directories(cwd / "in");
  generate(cwd, "1", "200", "1", "in/a.obj");
  // b takes long enough (0.5 s in Release) for the kill, as soon as a's line is there, to come
  // before it ends.
  generate(cwd, "3", "10000", "2", "in/b.obj");
  const pid_t batch = launch(cwd, {IGM_CLI_PATH, "batch", "in", "-o", "out"}, "first");
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t lines = 0;
  while (lines == 0 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(120)) {  // bound: 120 s
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    lines = lines_of(contents(cwd / "out/results.jsonl")).size();
  }
  kill(batch, SIGKILL);
  finish(cwd, batch, "first");
  lines = lines_of(contents(cwd / "out/results.jsonl")).size();
  REQUIRE(lines >= 1);
  REQUIRE_MESSAGE(lines == 1, "the batch ended before the kill: the test shows nothing");
  const Proc again = igm(cwd, {"batch", "in", "-o", "out"});
  INFO(again.err);
  CHECK(again.code == 0);
  CHECK(has(again.err, "2 meshes, 1 done already, 1 to run"));
  const std::map<std::string, std::string> expected = {{"a.obj", "certified"}, {"b.obj", "certified"}};
  CHECK(verdicts(cwd / "out") == expected);  // each once
  // Nothing left to do: a third run adds no line.
  CHECK(igm(cwd, {"batch", "in", "-o", "out"}).code == 0);
  CHECK(lines_of(contents(cwd / "out/results.jsonl")).size() == 2);
  fs::remove_all(cwd);
}

TEST_CASE("igm batch --timeout and the memory limits give timeout and out_of_memory") {
  const fs::path cwd = scratch("limits");
  generate(cwd, "3", "20000", "2", "slow.obj");  // ~1.3 s in Release
  const auto t0 = std::chrono::steady_clock::now();
  const Proc r = igm(cwd, {"batch", "slow.obj", "-o", "out", "--timeout", "0.2"});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(r.code == 0);
  const std::string line = contents(cwd / "out/results.jsonl");
  CAPTURE(line);
  CHECK(field(line, "verdict") == "timeout");
  CHECK(has(line, "\"signal\": 9"));
  CHECK(wall < (igm_test::kSanitized ? 5.0 : 1.0));  // killed at 0.2 s, not run to its end (1.3 s)
  CHECK(!has(r.out, "summary"));  // the one-MESH form prints its line only

  // The run's own memory stop (igm run --memory-limit-mb after --) counts as out_of_memory.
  generate(cwd, "4", "2000", "3", "g4.obj");
  const Proc m = igm(cwd, {"batch", "g4.obj", "-o", "mem", "--", "--memory-limit-mb", "1", "--layout", "spread"});
  CHECK(m.code == 0);
  const std::string mline = contents(cwd / "mem/results.jsonl");
  CAPTURE(mline);
  CHECK(field(mline, "verdict") == "out_of_memory");
  CHECK(field(mline, "error_kind") == "unsupported");
  CHECK(has(field(mline, "error"), "memory limit"));
  if (igm_test::kSanitized) {
    MESSAGE("--memory-mb (RLIMIT_AS) not tested under the sanitizers: their shadow memory needs terabytes of address space");
  } else {
    const Proc a = igm(cwd, {"batch", "g4.obj", "-o", "as", "--memory-mb", "20"});
    CHECK(a.code == 0);
    CHECK(field(contents(cwd / "as/results.jsonl"), "verdict") == "out_of_memory");
  }
  fs::remove_all(cwd);
}

TEST_CASE("GNU parallel running igm batch per mesh appends the lines of the sequential run") {
  const fs::path cwd = scratch("parallel");
  if (!has(igm(cwd, {"--help"}).out, "igm batch")) FAIL("igm --help does not list batch");
  const pid_t probe = launch(cwd, {"parallel", "--version"}, "probe");
  if (!has(finish(cwd, probe, "probe").out, "GNU parallel")) {
    MESSAGE("skipped: GNU parallel not installed (scripts/install-deps.sh installs it)");
    return;
  }
  generate(cwd, "1", "200", "1", "g1.obj");
  generate(cwd, "2", "300", "2", "g2.obj");
  generate(cwd, "0", "200", "3", "g0.off");
  std::ofstream(cwd / "points.off") << "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n";  // no faces
  const std::vector<std::string> files = {"g1.obj", "g2.obj", "g0.off", "points.off"};
  // The sequential run, from a LIST (a comment, a blank line, one absolute path).
  std::ofstream(cwd / "list.txt") << "# meshes\ng1.obj\n\n" << (cwd / "g2.obj").string() << "\n g0.off \npoints.off\n";
  const Proc seq = igm(cwd, {"batch", "list.txt", "-o", "seq"});
  INFO(seq.err);
  REQUIRE(seq.code == 0);
  CHECK(summary_count(seq.out, "certified") == 3);
  CHECK(summary_count(seq.out, "invalid_input") == 1);
  std::vector<std::string> argv = {"parallel", "--will-cite", "-j2", IGM_CLI_PATH, "batch", "{}", "-o", "par", ":::"};
  argv.insert(argv.end(), files.begin(), files.end());
  const Proc par = finish(cwd, launch(cwd, argv, "par"), "par");
  INFO(par.err);
  REQUIRE(par.code == 0);
  // The same lines but for the measured time and memory.
  const auto normalized = [](const std::string& text) {
    std::vector<std::string> out;
    for (const std::string& l : lines_of(text))
      out.push_back(std::regex_replace(l, std::regex(", \"seconds\": [0-9.]+, \"peak_mb\": [0-9.]+"), ""));
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto a = normalized(contents(cwd / "seq/results.jsonl")), b = normalized(contents(cwd / "par/results.jsonl"));
  CHECK(a.size() == 4);
  CHECK(a == b);
  CHECK(field(a.back(), "verdict") == "invalid_input");  // points.off sorts last
  CHECK(field(a.back(), "error_kind") == "no_faces");
  fs::remove_all(cwd);
}

TEST_CASE("igm batch usage errors exit 2") {
  const fs::path cwd = scratch("usage");
  generate(cwd, "1", "200", "1", "g1.obj");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"batch", "g1.obj"}, {"batch", "-o", "out"}, {"batch", "g1.obj", "-o", "out", "-j", "0"},
        {"batch", "g1.obj", "-o", "out", "--timeout", "x"}, {"batch", "g1.obj", "-o", "out", "--memory-mb", "-5"},
        {"batch", "g1.obj", "-o", "out", "--", "-o", "elsewhere"}, {"batch", "g1.obj", "-o", "out", "--bogus"},
        {"batch", "g1.obj", "g1.obj", "-o", "out"}, {"batch", "missing-list.txt", "-o", "out"}}) {
    CAPTURE(args.size());
    CAPTURE(args.back());
    const Proc r = igm(cwd, args);
    CHECK(r.code == 2);
    CHECK(has(r.err, "igm batch"));
  }
  CHECK(!fs::exists(cwd / "out/results.jsonl"));
  fs::remove_all(cwd);
}
