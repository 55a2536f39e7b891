// The igm command line tool. Subcommands are dispatched from a small table (kCommands) so
// that new ones (e.g. `run`, the full pipeline) are one entry and one function each.
// Exit codes: 0 success (a valid mesh for `info`), 2 invalid or unreadable input or a usage
// error.
#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "extract_command.h"
#include "batch_command.h"
#include "run_command.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitInvalid = 2;  // invalid or unreadable input
constexpr int kExitUsage = 2;    // bad command line

using Args = std::vector<std::string_view>;

struct Command {
  const char* name;
  const char* usage;
  int (*run)(const Args& args);  // args after the subcommand name
};

int cmd_help(const Args& args);
int cmd_info(const Args& args);
int cmd_generate(const Args& args);
int cmd_run(const Args& args) { return igm_cli::run_command(args); }
int cmd_extract(const Args& args) { return igm_cli::extract_command(args); }
int cmd_batch(const Args& args) { return igm_cli::batch_command(args); }

const Command kCommands[] = {
    {"run", "igm run MESH [-o DIR] [--quads Q | --edge-length H | --resolution N] [--layout spread|kite|paper]\n"
            "        [--map tutte|affine] [--root V] [--normal-form [--restarts K|auto]] [--cones A,B,C,D]\n"
            "        [--memory-limit-mb M]\n"
            "                                the whole pipeline: certified IGM, quad mesh, certificate, schema picture\n"
            "                                (genus 0: four pi-cones, --cones picks them as 0-based vertex ids)\n"
            "                                (writes DIR/NAME.igm.obj .igm.exact .quad.obj .cert.json .schema.svg\n"
            "                                .quad.svg; DIR=out)",
     cmd_run},
    {"extract", "igm extract IGM.obj|IGM.exact [-o QUAD.obj] [--json REPORT.json]\n"
                "                                the quad mesh of any IGM's integer isolines, exactly (the IGM certified\n"
                "                                first; default output NAME.quad.obj)",
     cmd_extract},
    {"batch", "igm batch DIR|LIST|MESH -o OUT [-j N] [--timeout S] [--memory-mb M] [-- RUN OPTIONS]\n"
              "                                `run` on every mesh of DIR (or of the LIST file, one path a line), each in\n"
              "                                a process of its own with a time and memory limit; one JSON line per mesh\n"
              "                                in OUT/results.jsonl (resumable; several batches may share OUT), a summary\n"
              "  igm batch --summary -o OUT    the summary of OUT/results.jsonl",
     cmd_batch},
    {"info", "igm info MESH                 read MESH (.obj .off .ply .stl), validate it, print what was found", cmd_info},
    {"generate", "igm generate --genus G --faces N [--seed S] OUT.(obj|off)\n"
                 "                                write a generated closed mesh of genus G with about N faces",
     cmd_generate},
    {"help", "igm help | igm --help         this text", cmd_help},
};

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "igm: integer grid maps of closed orientable triangle meshes\n\n"
               "usage:\n"
               "  igm                           `run` on a built-in generated mesh of genus 2 (outputs in ./out)\n");
  for (const Command& c : kCommands) std::fprintf(out, "  %s\n", c.usage);
  std::fprintf(out,
               "\nexit codes: 0 success (info: the mesh is valid after repairs; run, extract: outputs certified), 1 (run,\n"
               "extract) the certifier rejected an input IGM or an output, 2 invalid or unreadable\n"
               "input, or a usage error. Element ids in messages are 0-based (vertices and faces in file order).\n");
}

int usage_error(const std::string& message) {
  std::fprintf(stderr, "igm: %s\n\n", message.c_str());
  print_usage(stderr);
  return kExitUsage;
}

int cmd_help(const Args& args) {
  if (!args.empty()) return usage_error("help takes no arguments");
  print_usage(stdout);
  return kExitOk;
}

std::string ids_text(const std::vector<std::int64_t>& ids, std::size_t max) {
  std::string s;
  for (std::size_t i = 0; i < ids.size() && i < max; ++i) {
    if (i) s += ' ';
    s += std::to_string(ids[i]);
  }
  if (ids.size() > max) s += " ...";
  return s;
}

// Prints the report; returns the exit code.
int print_report(const std::string& name, const igm::MeshReport& r) {
  std::printf("mesh: %s\n", name.c_str());
  std::printf("vertices: %lld", static_cast<long long>(r.vertices));
  if (r.unreferenced_vertices > 0) std::printf(" (%lld unreferenced)", static_cast<long long>(r.unreferenced_vertices));
  std::printf("\nfaces: %lld", static_cast<long long>(r.faces));
  if (r.polygons > 0)
    std::printf(" (%lld polygons; %lld triangles after triangulation)", static_cast<long long>(r.polygons),
                static_cast<long long>(r.triangles));
  std::printf("\n");
  if (r.topology_checked) {
    std::printf("edges: %lld\n", static_cast<long long>(r.edges));
    std::printf("components: %lld\n", static_cast<long long>(r.components));
    std::printf("boundary loops: %lld\n", static_cast<long long>(r.boundary_loops));
    std::printf("non-manifold edges: %lld\n", static_cast<long long>(r.non_manifold_edges));
    std::printf("non-manifold vertices: %lld\n", static_cast<long long>(r.non_manifold_vertices));
    std::printf("orientable: %s\n", r.orientable ? "yes" : "no");
    std::printf("inconsistently oriented edges: %lld\n", static_cast<long long>(r.inconsistently_oriented_edges));
    std::printf("euler characteristic: %lld\n", static_cast<long long>(r.euler_characteristic));
  } else if (r.faces > 0 && r.vertices > 0) {
    std::printf("topology: not checked (the faces are malformed, see problems)\n");
  }
  if (r.genus >= 0)
    std::printf("genus: %d\n", r.genus);
  else
    std::printf("genus: undefined (invalid mesh)\n");
  for (const std::string& w : r.warnings) std::printf("warning: %s\n", w.c_str());
  for (const igm::MeshProblem& p : r.problems) {
    std::printf("problem: %s (%lld): %s\n", igm::to_string(p.kind), static_cast<long long>(p.count), p.message.c_str());
    if (!p.elements.empty()) std::printf("  elements: %s\n", ids_text(p.elements, 20).c_str());
  }
  if (r.problems.empty()) {
    std::printf("status: valid\n");
    return kExitOk;
  }
  std::printf("status: invalid (%zu problem kinds)\n", r.problems.size());
  const igm::MeshProblem& first = r.problems.front();
  std::fprintf(stderr, "igm: %s: invalid mesh: %s: %s\n", name.c_str(), igm::to_string(first.kind),
               first.message.c_str());
  return kExitInvalid;
}

int cmd_info(const Args& args) {
  if (args.size() != 1) return usage_error("info takes exactly one mesh file");
  if (!args[0].empty() && args[0][0] == '-') return usage_error("unknown option '" + std::string(args[0]) + "'");
  const std::string path(args[0]);
  igm::PolygonSoup soup;
  try {
    soup = igm::read_soup(std::filesystem::path(path));
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: cannot read the mesh: %s\n", e.what());  // the message names the path
    return kExitInvalid;
  }
  return print_report(path, igm::inspect(soup));
}

bool parse_int(std::string_view s, std::int64_t& out) {
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

int cmd_generate(const Args& args) {
  igm::GenerateOptions o;
  bool have_genus = false, have_faces = false;
  std::string out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--genus" || a == "--faces" || a == "--seed") {
      if (i + 1 >= args.size()) return usage_error(std::string(a) + " needs a value");
      std::int64_t v = 0;
      if (!parse_int(args[i + 1], v))
        return usage_error(std::string(a) + " needs an integer, got '" + std::string(args[i + 1]) + "'");
      ++i;
      if (a == "--genus") {
        if (v < 0 || v > 100000) return usage_error("--genus must be in 0..100000");
        o.genus = static_cast<int>(v);
        have_genus = true;
      } else if (a == "--faces") {
        if (v < 1 || v > (std::int64_t{1} << 28)) return usage_error("--faces must be in 1..2^28");
        o.faces = v;
        have_faces = true;
      } else {
        if (v < 0) return usage_error("--seed must be >= 0");
        o.seed = static_cast<std::uint64_t>(v);
      }
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + std::string(a) + "'");
    } else {
      if (!out.empty()) return usage_error("generate takes one output file");
      out = std::string(a);
    }
  }
  if (!have_genus || !have_faces) return usage_error("generate needs --genus and --faces");
  if (out.empty()) return usage_error("generate needs an output file OUT.obj or OUT.off");
  const std::filesystem::path path(out);
  std::string ext = path.extension().string();
  if (ext != ".obj" && ext != ".off") return usage_error("the output file must end in .obj or .off");
  try {
    const igm::PolygonSoup soup = igm::generate_closed_mesh(o);
    const igm::ValidMesh m = igm::validate(soup);  // the generator's contract, checked
    std::vector<std::array<int, 3>> tris(m.mesh.num_faces());
    for (int f = 0; f < m.mesh.num_faces(); ++f) tris[f] = m.mesh.face_vertices(f);
    if (ext == ".obj")
      igm::write_obj(path, m.positions, tris);
    else
      igm::write_off(path, m.positions, tris);
    std::printf("wrote %s: %d vertices, %d faces, genus %d\n", out.c_str(), m.mesh.num_vertices(), m.mesh.num_faces(),
                m.genus);
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: generate: %s\n", e.what());
    return kExitInvalid;
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 2) return igm_cli::run_default();
    const std::string_view name = argv[1];
    if (name == "--help" || name == "-h") return cmd_help({});
    const Args rest(argv + 2, argv + argc);
    for (const Command& c : kCommands)
      if (name == c.name) return c.run(rest);
    if (!name.empty() && name[0] == '-') return usage_error("unknown option '" + std::string(name) + "'");
    return usage_error("unknown command '" + std::string(name) + "'");
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: %s\n", e.what());
    return kExitInvalid;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igm: internal error: %s\n", e.what());
    return 3;
  }
}
