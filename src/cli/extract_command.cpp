#include "extract_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include "certify/certify.h"
#include "certify/obj.h"
#include "igm/core/error.h"
#include "igm/extract/isolines.h"
#include "igm/extract/quad_defects.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/output/igm_mesh.h"

namespace igm_cli {

namespace {

constexpr int kExitCertified = 0, kExitRejected = 1, kExitInput = 2, kExitInternal = 3;
constexpr std::size_t kWitnessesPrinted = 10;

int usage(const std::string& message) {
  std::fprintf(
      stderr,
      "igm extract: %s\nusage: igm extract IGM.obj|IGM.exact [-o QUAD.obj] [--json REPORT.json]\n"
      "                   [--boundary] [--components]\n"
      "  the quad mesh of the IGM's integer isolines, located exactly; the IGM is read with\n"
      "  exact UVs (decimals or p/q) and certified first. Default output: NAME.quad.obj here.\n"
      "  --boundary accepts IGMs of surfaces with boundary (every boundary edge on an integer\n"
      "  isoline), --components several connected components (as igm-certify's flags)\n"
      "  exit 0 quads certified, 1 the IGM (or the quads) rejected by the certifier, 2 unreadable\n"
      "  input or usage, 3 internal error\n",
      message.c_str());
  return kExitInput;
}

// The report's failed checks and their first witnesses, for humans.
void print_witnesses(const igm::certify::Report& r) {
  for (const igm::certify::CheckResult& c : r.checks) {
    if (c.passed()) continue;
    std::printf("  check %d %s: %s, %lld offending\n", c.id, c.name.c_str(),
                igm::certify::to_string(c.status), static_cast<long long>(c.offending));
    for (std::size_t i = 0; i < c.witnesses.size() && i < kWitnessesPrinted; ++i) {
      const igm::certify::Witness& w = c.witnesses[i];
      std::printf("    %s", w.kind.c_str());
      for (std::int64_t id : w.ids) std::printf(" %lld", static_cast<long long>(id));
      std::printf(": %s", w.reason.c_str());
      for (const auto& [name, value] : w.values)
        std::printf(", %s = %s", name.c_str(), value.c_str());
      std::printf("\n");
    }
  }
}

std::string stats_json(const igm::IsolineQuads& q, const std::string& defects) {
  const igm::IsolineStats& s = q.stats;
  std::ostringstream o;
  o << "{\"quads\": " << q.quads.size() << ", \"vertices\": " << q.vertices.size()
    << ", \"edges\": " << q.num_edges << ", \"genus\": " << q.genus
    << ", \"boundary_loops\": " << q.boundary_loops
    << ", \"grid_points_on_vertices\": " << s.grid_points_on_vertices
    << ", \"grid_points_on_edges\": " << s.grid_points_on_edges
    << ", \"grid_points_in_faces\": " << s.grid_points_in_faces << ", \"cones\": " << s.cones
    << ", \"grid_points_on_boundary\": " << s.grid_points_on_boundary
    << ", \"boundary_corners\": " << s.boundary_corners
    << ", \"traces\": " << s.traces << ", \"trace_steps\": " << s.trace_steps
    << ", \"max_trace_steps\": " << s.max_trace_steps
    << ", \"vertex_crossings\": " << s.vertex_crossings << ", \"seconds\": " << s.seconds_total;
  if (!defects.empty()) o << ", \"quad_defects\": \"" << defects << "\"";  // ids, digits and plain words only
  o << "}";
  return o.str();
}

// {"extractor", "exit_code", "extraction": stats or null, "igm": report, "quad": report or null}.
void write_json(const std::string& path, int code, const igm::certify::Report& igm_report,
                const igm::IsolineQuads* quads, const igm::certify::Report* quad_report,
                const std::string& defects = "") {
  std::string s = "{\n\"extractor\": \"igm extract\",\n\"exit_code\": " + std::to_string(code) +
                  ",\n\"extraction\": ";
  s += quads ? stats_json(*quads, defects) : std::string("null");
  s += ",\n\"igm\": " + igm::certify::to_json(igm_report) + ",\n\"quad\": ";
  s += quad_report ? igm::certify::to_json(*quad_report) : std::string("null\n");
  s += "}\n";
  igm::write_text_file(path, s);
}

// NAME of NAME.obj, NAME.exact, NAME.igm.obj, NAME.igm.exact.
std::string base_name(const std::string& path) {
  std::filesystem::path p = std::filesystem::path(path).filename();
  p = p.stem();
  if (p.extension() == ".igm") p = p.stem();
  return p.string();
}

}  // namespace

int extract_command(const std::vector<std::string_view>& args) {
  std::string in_path, out_path, json_path;
  igm::IsolineOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {  // bound: the arguments
    const std::string_view a = args[i];
    if (a == "--boundary") {
      options.allow_boundary = true;
    } else if (a == "--components") {
      options.allow_components = true;
    } else if (a == "-o" || a == "--json") {
      if (i + 1 >= args.size()) return usage(std::string(a) + " needs a file name");
      (a == "-o" ? out_path : json_path) = std::string(args[++i]);
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else {
      if (!in_path.empty()) return usage("extract takes one IGM file");
      in_path = std::string(a);
    }
  }
  if (in_path.empty()) return usage("extract needs an IGM file");
  if (out_path.empty()) out_path = base_name(in_path) + ".quad.obj";
  try {
    const std::string text = igm::read_file_bytes(in_path);
    // The certifier's reader: exact UVs; a triangle mesh with a UV at every corner, else unreadable
    // (the certifier's own message, with the line).
    igm::certify::ObjReadResult obj = igm::certify::read_obj(text);
    bool triangles = obj.ok && obj.mesh.num_faces() > 0;
    for (std::int64_t f = 0; triangles && f < obj.mesh.num_faces(); ++f) {  // bound: F
      triangles = obj.mesh.face_begin[f + 1] - obj.mesh.face_begin[f] == 3;
      for (std::int64_t k = obj.mesh.face_begin[f]; triangles && k < obj.mesh.face_begin[f + 1];
           ++k)
        triangles = obj.mesh.corner_uv[k] >= 0;
    }
    if (!triangles) {
      igm::certify::Report r = igm::certify::certify_igm_text(text);
      r.source = in_path;
      std::fprintf(stderr, "igm extract: %s\n", igm::certify::summary(r).c_str());
      if (!json_path.empty()) write_json(json_path, kExitInput, r, nullptr, nullptr);
      return kExitInput;
    }
    igm::IsolineInput in;
    const igm::certify::ObjMesh& m = obj.mesh;
    in.triangles.resize(static_cast<std::size_t>(m.num_faces()));
    in.corner_uv.resize(in.triangles.size());
    for (std::size_t f = 0; f < in.triangles.size(); ++f)  // bound: F
      for (int k = 0; k < 3; ++k) {
        const std::int64_t corner = m.face_begin[f] + k;
        in.triangles[f][k] = m.corner_vertex[corner];
        const auto& uv = m.uv[m.corner_uv[corner]];
        in.corner_uv[f][k] = {uv[0], uv[1]};
      }
    // Positions from the `v` lines (the certifier's reader checks them but keeps no values).
    in.positions = igm::read_soup(text, igm::MeshFormat::Obj).positions;
    if (static_cast<std::int64_t>(in.positions.size()) != m.num_vertices)
      throw igm::Error(igm::ErrorKind::Parse, "the OBJ readers disagree on the number of vertices");

    const auto t0 = std::chrono::steady_clock::now();
    igm::IsolineResult x = igm::extract_isolines(in, options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    x.report.source = in_path;
    if (!x.quads) {
      const int code = igm::certify::exit_code(x.report);
      std::printf("NOT AN IGM: %s\n", igm::certify::summary(x.report).c_str());
      print_witnesses(x.report);
      const std::int64_t components = static_cast<std::int64_t>(x.report.components.size());
      if (x.report.num_boundary_edges > 0 && !options.allow_boundary)
        std::printf("  (the IGM has %lld boundary edges: --boundary accepts them)\n",
                    static_cast<long long>(x.report.num_boundary_edges));
      if (components > 1 && !options.allow_components)
        std::printf("  (the IGM has %lld components: --components accepts them)\n",
                    static_cast<long long>(components));
      if (!json_path.empty()) write_json(json_path, code, x.report, nullptr, nullptr);
      return code;
    }
    const igm::IsolineQuads& q = *x.quads;
    // Pure quads of the IGM's genus; with --boundary / --components also its boundary loops and
    // each component's (genus, loops).
    igm::certify::Report quad_report = igm::certify_isoline_quads(x, options);
    quad_report.source = out_path;
    std::ostringstream obj_text;
    igm::QuadMesh mesh;
    mesh.positions = q.positions;
    mesh.quads = q.quads;
    igm::write_quad_obj(obj_text, mesh);
    igm::write_text_file(out_path, obj_text.str());
    const int code = quad_report.valid() ? kExitCertified : kExitRejected;
    // Why the quads are refused, when they are (a grid too coarse for the cones).
    const std::string why = quad_report.valid() ? "" : igm::describe_quad_defects(q, igm::find_quad_defects(q, 20));
    if (!json_path.empty()) write_json(json_path, code, x.report, &q, &quad_report, why);
    const igm::IsolineStats& s = q.stats;
    std::printf(
        "%zu quads, %zu vertices (%lld on mesh vertices, %lld on edges, %lld in triangles; %lld "
        "cones), "
        "genus %d, %d boundary loops, from %zu triangles in %.3f s; wrote %s: %s\n",
        q.quads.size(), q.vertices.size(), static_cast<long long>(s.grid_points_on_vertices),
        static_cast<long long>(s.grid_points_on_edges),
        static_cast<long long>(s.grid_points_in_faces), static_cast<long long>(s.cones), q.genus,
        q.boundary_loops, in.triangles.size(), seconds, out_path.c_str(),
        quad_report.valid() ? "certified" : "NOT CERTIFIED");
    if (!quad_report.valid()) {
      if (!why.empty()) std::printf("  %s\n", why.c_str());
      print_witnesses(quad_report);
    }
    return code;
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm extract: %s: %s\n", in_path.c_str(), e.what());
    return e.kind() == igm::ErrorKind::Internal ? kExitInternal : kExitInput;
  }
}

}  // namespace igm_cli
