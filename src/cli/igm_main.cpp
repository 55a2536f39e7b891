// The igm command line tool. Subcommands are dispatched from a small table (kCommands) so
// that new ones (e.g. `run`, the full pipeline) are one entry and one function each.
// Exit codes: 0 success (a valid mesh for `info`), 2 invalid or unreadable input or a usage
// error.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "igm/core/error.h"
#include "igm/features/feature_edges.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/pipeline/pipeline.h"
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
    {"run", "igm run MESH [-o DIR] [--quads Q | --edge-length H | --resolution N] [--layout field|spread|kite|paper]\n"
            "        [--map tutte|affine] [--no-smooth] [--smooth-iterations N] [--smooth-seconds S]\n"
            "        [--split-nonmanifold] [--root V] [--normal-form [--restarts K|auto]] [--cones A,B,C,D]\n"
            "        [--memory-limit-mb M]\n"
            "                                the whole pipeline: certified IGM, quad mesh, certificate, schema picture\n"
            "                                (the field layout: cones from a cross field, the topological one where it\n"
            "                                cannot finish; --layout spread, genus 0: four pi-cones, --cones picks them\n"
            "                                as 0-based vertex ids; open\n"
            "                                surfaces: boundaries on integer isolines; several components: each its\n"
            "                                own IGM, one output; `igm run --help` for every option)\n"
            "                                (writes DIR/NAME.igm.obj .igm.exact .quad.obj .cert.json .schema.svg\n"
            "                                .quad.svg; DIR=out)",
     cmd_run},
    {"extract", "igm extract IGM.obj|IGM.exact [-o QUAD.obj] [--json REPORT.json] [--boundary] [--components]\n"
                "                                the quad mesh of any IGM's integer isolines, exactly (the IGM certified\n"
                "                                first; default output NAME.quad.obj); --boundary: surfaces with boundary,\n"
                "                                --components: several components",
     cmd_extract},
    {"batch", "igm batch DIR|LIST|MESH -o OUT [-j N] [--timeout S] [--memory-mb M] [-- RUN OPTIONS]\n"
              "                                `run` on every mesh of DIR (or of the LIST file, one path a line), each in\n"
              "                                a process of its own with a time and memory limit; one JSON line per mesh\n"
              "                                in OUT/results.jsonl (resumable; several batches may share OUT), a summary\n"
              "  igm batch --summary -o OUT    the summary of OUT/results.jsonl",
     cmd_batch},
    {"info", "igm info MESH [--split-nonmanifold]\n"
             "                                read MESH (.obj .off .ply .stl), validate it, print what was found (with\n"
             "                                boundaries or several components: each surface; --split-nonmanifold cuts\n"
             "                                non-manifold vertices and edges apart first)",
     cmd_info},
    {"generate", "igm generate --genus G --faces N [--boundaries B] [--seed S] OUT.(obj|off)\n"
                 "                                write a generated mesh of genus G with about N faces (closed, or with B\n"
                 "                                boundary loops)",
     cmd_generate},
    {"help", "igm help | igm --help         this text", cmd_help},
};

void print_usage(std::FILE* out) {
  std::fprintf(out,
               "igm: certified integer grid maps and quad meshes of orientable triangle meshes\n"
               "     (closed or open, one or several components)\n\n"
               "usage:\n"
               "  igm                           `run` on a built-in generated mesh of genus 2 (outputs in ./out)\n");
  for (const Command& c : kCommands) std::fprintf(out, "  %s\n", c.usage);
  std::fprintf(out,
               "\nexit codes: 0 success (info: `igm run` accepts the mesh after repairs; run, extract: outputs\n"
               "certified), 1 (run,\n"
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

// Whether `igm run` maps the mesh as one or several surfaces (validate_surfaces): several
// components and boundary loops are facts, not problems.
bool surface_fact(igm::ErrorKind kind) {
  return kind == igm::ErrorKind::Boundary || kind == igm::ErrorKind::SeveralComponents;
}

// The report of `igm info`: the counts, the genus (per surface where there are several or open
// ones), the problems `igm run` refuses (with --split-nonmanifold: what remains after the cuts)
// with how to go on, the surfaces and the status; returns the exit code (0: `igm run` accepts it).
int print_report(const std::string& name, const igm::PolygonSoup& soup, const igm::MeshReport& r, bool split) {
  // What `igm run` makes of it: its surfaces, or why not.
  igm::SurfaceOptions o;
  o.split_nonmanifold = split;
  std::optional<igm::SurfaceSet> set;
  std::optional<igm::Error> refused;
  if (r.topology_checked || r.problems.empty()) {
    try {
      set = igm::validate_surfaces(soup, o);
    } catch (const igm::Error& e) {
      refused = e;
    }
  }
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
  const bool one_closed = set && set->components.size() == 1 && set->components[0].boundary_loops.empty();
  if (r.genus >= 0 && !(set && !one_closed)) {
    std::printf("genus: %d\n", r.genus);
  } else if (set) {  // per surface, in the order listed below
    std::string list;
    for (std::size_t i = 0; i < set->components.size(); ++i) {
      if (i == 20) {
        list += ", ...";
        break;
      }
      list += (i ? ", " : "") + std::to_string(set->components[i].genus);
    }
    std::printf("genus: %s (per surface)\n", list.c_str());
  } else {
    std::printf("genus: undefined (invalid mesh)\n");
  }
  for (const std::string& w : r.warnings) std::printf("warning: %s\n", w.c_str());
  // The problems `igm run` refuses: all of inspect()'s but the surfaces' facts; with the split,
  // only what remains after it.
  std::vector<const igm::MeshProblem*> problems;
  if (!set)
    for (const igm::MeshProblem& p : r.problems)
      if (!surface_fact(p.kind) && !(split && (p.kind == igm::ErrorKind::NonManifoldEdge ||
                                               p.kind == igm::ErrorKind::NonManifoldVertex)))
        problems.push_back(&p);
  for (const igm::MeshProblem* p : problems) {
    std::printf("problem: %s (%lld): %s\n", igm::to_string(p->kind), static_cast<long long>(p->count), p->message.c_str());
    if (!p->elements.empty()) std::printf("  elements: %s\n", ids_text(p->elements, 20).c_str());
  }
  if (refused && problems.empty()) std::printf("problem: %s\n", refused->what());  // found only by the split
  if (refused) {
    const std::string hint = igm::split_nonmanifold_hint(soup, o, *refused, "--split-nonmanifold");
    if (!hint.empty()) std::printf("hint: %s\n", hint.c_str());
  }
  if (set && !one_closed) {
    std::printf("surfaces: %zu\n", set->components.size());
    for (std::size_t i = 0; i < set->components.size(); ++i) {
      const igm::SurfaceComponent& c = set->components[i];
      std::printf(
          "surface %zu: faces %zu, vertices %zu, boundary loops %zu, genus %d, "
          "euler characteristic %lld, first face %lld\n",
          i, c.triangles.size(), c.positions.size(), c.boundary_loops.size(), c.genus,
          static_cast<long long>(c.euler_characteristic), static_cast<long long>(c.input_face[0]));
    }
  }
  if (set)  // the warnings not printed already (the cuts, and the repairs after them)
    for (const std::string& w : set->warnings)
      if (std::find(r.warnings.begin(), r.warnings.end(), w) == r.warnings.end())
        std::printf("surfaces warning: %s\n", w.c_str());
  if (set) {  // the sharp features `igm run` measures (default options: the default quad count)
    double area = 0;
    for (const igm::SurfaceComponent& c : set->components)
      for (const auto& t : c.triangles) {
        const igm::Vec3d &p0 = c.positions[t[0]], &p1 = c.positions[t[1]], &p2 = c.positions[t[2]];
        const double ux = p1.x - p0.x, uy = p1.y - p0.y, uz = p1.z - p0.z;
        const double vx = p2.x - p0.x, vy = p2.y - p0.y, vz = p2.z - p0.z;
        const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
        area += 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
      }
    igm::FeatureOptions fo;
    fo.quad_size = std::sqrt(area / static_cast<double>(igm::kDefaultQuads));
    if (!std::isfinite(fo.quad_size)) fo.quad_size = 0;
    igm::FeatureStats total;
    for (const igm::SurfaceComponent& c : set->components) {
      const igm::TriMesh mesh = igm::TriMesh::from_triangles(static_cast<int>(c.positions.size()), c.triangles, true);
      const igm::FeatureStats f = igm::detect_features(mesh, c.positions, {}, fo).stats;
      total.edges += f.edges;
      total.curves += f.curves;
      total.corners += f.corners;
      total.dropped_chains += f.dropped_chains;
      total.short_chains += f.short_chains;
      total.short_edges += f.short_edges;
    }
    std::printf("features: %d edges, %d curves, %d corners (dihedral >= %g deg; %d short chains dropped; at %lld quads "
                "%d chains of %d edges shorter than %g quad edges not followed)\n",
                total.edges, total.curves, total.corners, fo.angle_degrees, total.dropped_chains,
                static_cast<long long>(igm::kDefaultQuads), total.short_chains, total.short_edges, fo.min_quad_edges);
  }
  if (set) {
    if (one_closed)
      std::printf("status: valid\n");
    else
      std::printf("status: valid (%zu surface%s: `igm run%s` maps each, boundaries on integer isolines)\n",
                  set->components.size(), set->components.size() == 1 ? "" : "s", split ? " --split-nonmanifold" : "");
    return kExitOk;
  }
  std::printf("status: invalid\n");
  const std::string first = refused ? refused->what()
                                    : std::string(igm::to_string(problems.front()->kind)) + ": " + problems.front()->message;
  std::fprintf(stderr, "igm: %s: invalid mesh: %s\n", name.c_str(), first.c_str());
  return kExitInvalid;
}

int cmd_info(const Args& args) {
  bool split = false;
  std::string path;
  for (const std::string_view a : args) {
    if (a == "--split-nonmanifold") {
      split = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage_error("unknown option '" + std::string(a) + "'");
    } else {
      if (!path.empty()) return usage_error("info takes exactly one mesh file");
      path = std::string(a);
    }
  }
  if (path.empty()) return usage_error("info takes exactly one mesh file");
  igm::PolygonSoup soup;
  try {
    soup = igm::read_soup(std::filesystem::path(path));
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: cannot read the mesh: %s\n", e.what());  // the message names the path
    return kExitInvalid;
  }
  return print_report(path, soup, igm::inspect(soup), split);
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
    if (a == "--genus" || a == "--faces" || a == "--seed" || a == "--boundaries") {
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
      } else if (a == "--boundaries") {
        if (v < 0 || v > 100000) return usage_error("--boundaries must be in 0..100000");
        o.boundaries = static_cast<int>(v);
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
    const igm::PolygonSoup soup = igm::generate_mesh(o);
    // The generator's contract, checked: one surface (closed: validate()'s mesh).
    igm::SurfaceOptions check;
    check.allow_boundary = o.boundaries > 0;
    check.allow_components = false;
    const igm::SurfaceSet set = igm::validate_surfaces(soup, check);
    const igm::SurfaceComponent& m = set.components.front();
    if (m.genus != o.genus || m.boundary_loops.size() != static_cast<std::size_t>(o.boundaries))
      throw igm::Error(igm::ErrorKind::Internal,
                       "the generated mesh has genus " + std::to_string(m.genus) + " and " +
                           std::to_string(m.boundary_loops.size()) + " boundary loops");
    if (ext == ".obj")
      igm::write_obj(path, m.positions, m.triangles);
    else
      igm::write_off(path, m.positions, m.triangles);
    std::printf("wrote %s: %zu vertices, %zu faces, genus %d", out.c_str(), m.positions.size(),
                m.triangles.size(), m.genus);
    if (o.boundaries > 0) std::printf(", %d boundary loops", o.boundaries);
    std::printf("\n");
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
