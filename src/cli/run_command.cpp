#include "run_command.h"

#include <sys/resource.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <memory>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>

#include "igm/core/error.h"
#include "igm/core/threads.h"
#include "igm/core/memory.h"
#include "igm/mesh/generate.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/validate.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/output/igm_mesh.h"
#include "igm/output/quad_svg.h"
#include "igm/output/schema_svg.h"
#include "igm/pipeline/pipeline.h"

namespace igm_cli {

namespace {

constexpr int kExitCertified = 0, kExitRejected = 1, kExitInput = 2;

bool parse_int(std::string_view s, long long& out) {
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

// The options (to stderr after a usage error, exit 2; to stdout for --help, exit 0).
int usage(const std::string& message, bool help = false) {
  std::fprintf(help ? stdout : stderr,
               "%s%susage: igm run MESH [-o DIR] [--quads Q | --edge-length H | --resolution N]\n"
               "               [--layout field|spread|kite|paper] [--field-alignment W] [--map tutte|affine]\n"
               "               [--no-smooth] [--root V]\n"
               "               [--normal-form [--restarts K|auto]] [--cones A,B,C,D] [--memory-limit-mb M]\n"
               "               [--smooth-iterations N] [--smooth-min-decrease X] [--smooth-seconds S] [--threads N]\n"
               "               [--feature-angle DEG] [--feature-min-quads K] [--no-features] [--features FILE]\n"
               "  writes DIR/NAME.igm.obj, NAME.igm.exact, NAME.quad.obj, NAME.cert.json, NAME.schema.svg,\n"
               "  NAME.quad.svg (a shaded picture of the quads, cones marked by valence)\n"
               "  --quads Q       about Q quads (default %lld): each layout edge gets round(length / H) quads,\n"
               "                  H chosen so that the count is nearest to Q\n"
               "  --edge-length H quads of 3D edge length about H (in the mesh's units)\n"
               "  --resolution N  N quads along every layout edge, N x N per layout quad (1..1024)\n"
               "                  whatever the size, every surface gets at least the quads its layout needs\n"
               "                  for a manifold quad mesh (the floor: e.g. 3 along a torus's sides, 2 x 2\n"
               "                  per unit on a sphere unless 1 x 1); the run says where it raised them\n"
               "  --layout L      field (default): cones and patches from a cross field on any surface\n"
               "                  (docs/field.md), falling back to the topological layout (spread; genus 0:\n"
               "                  the orbifold) where a step cannot finish (said in cert.json's\n"
               "                  stats.layout_fallback and on the terminal); the topological layouts of the\n"
               "                  polygonal schema (genus >= 1): spread (root of valence 4g, 4g-4 vertices of\n"
               "                  valence 5), kite (4g at the root and the centre) or paper (Livesu's\n"
               "                  template: 8g at the root, 3g at the centre). --cones and --normal-form ask\n"
               "                  for the topological layout; --root, --restarts, --memory-limit-mb concern it\n"
               "  --field-alignment W  the field layout's curvature alignment weight (default 100,\n"
               "                  then other attempts; 0: the smoothest field), this one alone\n"
               "  --map M         each layout quad mapped onto its rectangle by a Tutte map from its own\n"
               "                  geometry (tutte, default) or through the disk's map (affine, the paper's)\n"
               "  --no-smooth     keep the layout's map (default: smoothed, every iterate a certified IGM)\n"
               "  --smooth-iterations N  at most N Newton iterations (default 100, and past 100k IGM triangles\n"
               "                  at most max(5, 10^7 / triangles)); smoothing also stops after\n"
               "                  an iteration that lowers the energy by less than --smooth-min-decrease X of\n"
               "                  it (default 0.001) or two steps in a row below 1/200 of the Newton step\n"
               "  --smooth-seconds S  also stop after S seconds of wall time (default 0: never; with S the\n"
               "                  result depends on the machine's speed and load)\n"
               "  --feature-angle DEG  sharp features: edges whose faces' normals differ by >= DEG degrees\n"
               "                  (0..180, default 35; short chains of scans dropped, docs/quality.md); measured\n"
               "                  (cert.json quality.features: the share of their length on quad edges), and\n"
               "                  by the field layout followed: every kept feature edge on quad edges, certified\n"
               "  --feature-min-quads K  detected feature chains shorter than K quad edges are measured but not\n"
               "                  followed (default 6; 0: all followed; the quad edge from --quads or --edge-length)\n"
               "  --no-features   detect no sharp edge (only those of --features)\n"
               "  --features FILE more feature edges: one pair \"i j\" of 0-based vertex ids per line, '#' comments\n"
               "  --threads N     threads for the parallel stages (default 0: IGM_THREADS if set, else all\n"
               "                  cores); the outputs are the same for any N\n"
               "  --split-nonmanifold  cut non-manifold vertices and edges apart (each cut named in a warning)\n"
               "                  and map the resulting open surfaces\n"
               "  --cones A,B,C,D genus 0: the four cone vertices (0-based input ids) in path order\n"
               "  --memory-limit-mb M  genus >= 1: stop with exit 2 in the arrangement once the rest would\n"
               "                  need more than M MB (default: this machine's memory)\n"
               "  --restarts K    with --normal-form, 0..64 or auto: where the loops added more than 2 %% of\n"
               "                  the vertices, cut K copies with shuffled vertex ids too, keep the fewest\n"
               "                  (auto: clamp(5e6 / (faces x genus^2), 0, 15) copies)\n",
               help ? "" : "igm run: ", help ? "" : (message + "\n").c_str(), static_cast<long long>(igm::kDefaultQuads));
  return help ? 0 : kExitInput;
}

bool parse_double(std::string_view s, double& out) {
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

// The run's peak memory: the stages' peaks (each stage resets the process's peak) and the peak
// since the last of them.
double peak_rss_mb(const std::vector<const igm::PipelineStats*>& runs) {
  double mb = igm::peak_resident_mb();
  for (const igm::PipelineStats* st : runs)
    for (const igm::StageEvent& e : st->stages) mb = std::max(mb, e.peak_mb);
  return mb;
}

// "stages": [{"stage": ..., "seconds": ..., "peak_mb": ...}, ...] of one run.
std::string stages_json(const igm::PipelineStats& st) {
  std::ostringstream s;
  s << "[";
  for (std::size_t i = 0; i < st.stages.size(); ++i)
    s << (i ? ", " : "") << "{\"stage\": \"" << st.stages[i].stage << "\", \"seconds\": " << st.stages[i].seconds
      << ", \"cpu_seconds\": " << st.stages[i].cpu_seconds << ", \"peak_mb\": " << st.stages[i].peak_mb << "}";
  s << "]";
  return s.str();
}

template <class Writer>
void write_file(const std::filesystem::path& path, Writer&& writer) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw igm::Error(igm::ErrorKind::Io, "cannot write " + path.string());
  writer(out);
  out.flush();
  if (!out) throw igm::Error(igm::ErrorKind::Io, "error while writing " + path.string());
}

std::string json_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '"' || c == '\\') r += '\\', r += c;
    else if (static_cast<unsigned char>(c) < 0x20) r += ' ';
    else r += c;
  }
  return r;
}

// The field layout's fallback as JSON: null when none, else its stage and reason.
std::string fallback_json(const igm::PipelineStats& st) {
  return st.layout_fallback.empty() ? "null" : "\"" + json_escape(st.layout_fallback) + "\"";
}

// The field layout's statistics as JSON (null when it was not tried).
std::string field_json(const igm::PipelineStats& st) {
  if (st.layout != "field" && st.layout_fallback.empty()) return "null";
  const igm::CrossFieldStats& f = st.cross_field;
  std::string v = "{";
  for (int k = 0; k < 9; ++k)
    if (k != 4 && f.valence_count[k] > 0) v += (v.size() > 1 ? ", \"" : "\"") + std::to_string(k) + "\": " + std::to_string(f.valence_count[k]);
  v += "}";
  const igm::FieldLayoutStats& l = st.field_layout;
  return "{\"cone_valences\": " + v + ", \"curves\": " + std::to_string(l.trace.curves) + ", \"patches\": " +
         std::to_string(l.patches) + ", \"t_junctions\": " + std::to_string(l.t_junctions) + ", \"pattern_patches\": " + std::to_string(l.pattern_patches) + ", \"reflex_cuts\": " + std::to_string(l.reflex_cuts) + ", \"rounds\": " +
         std::to_string(l.rounds) + ", \"banned_rays\": " + std::to_string(l.banned_rays) + ", \"seeds\": " +
         std::to_string(l.seeds) + ", \"feature_walls\": " + std::to_string(st.feature_walls) +
         ", \"features_dropped\": " + std::to_string(st.features_dropped) + ", \"features_failure\": " +
         (st.features_failure.empty() ? std::string("null") : "\"" + json_escape(st.features_failure) + "\"") +
         ", \"quantize_deviation\": " + std::to_string(st.quantize.deviation) + "}";
}

// The options with a line per stage, and per smoothing iteration once it has run 2 s (at most one a
// second), on the terminal.
igm::PipelineOptions with_progress(igm::PipelineOptions options) {
  options.measure_stage_memory = true;
  options.progress = [](const igm::StageEvent& e) {
    std::printf("[%-8s] %8.3f s (cpu %7.2f s) %6.0f MB  %s\n", e.stage.c_str(), e.seconds, e.cpu_seconds, e.peak_mb,
                e.detail.c_str());
    std::fflush(stdout);
  };
  auto last = std::make_shared<double>(0.0);
  options.smooth_progress = [last](const igm::SmoothProgress& p) {
    if (p.seconds < 2 || p.seconds < *last + 1) return;
    *last = p.seconds;
    std::printf("[smooth  ] %8.3f s  iteration %d: energy %.6g\n", p.seconds, p.iteration, p.energy);
    std::fflush(stdout);
  };
  return options;
}

void create_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw igm::Error(igm::ErrorKind::Io, "cannot create output folder " + dir.string() + ": " + ec.message());
}

// The last line of a run: both certifier verdicts; the exit code.
int print_verdict(const igm::certify::Report& igm_report, const igm::certify::Report& quad_report) {
  if (!igm_report.valid() || !quad_report.valid()) {
    std::printf("NOT CERTIFIED: %s | %s\n", igm::certify::summary(igm_report).c_str(),
                igm::certify::summary(quad_report).c_str());
    return kExitRejected;
  }
  std::printf("certified: %s\n", igm::certify::summary(igm_report).c_str());
  return kExitCertified;
}

// Creates DIR and writes NAME.igm.obj (doubles), NAME.igm.exact, NAME.quad.obj and NAME.quad.svg
// (formatted on `threads` threads, as the run's stages); returns the path maker DIR/NAME + suffix
// for the run's other files.
std::function<std::filesystem::path(const char*)> write_outputs(const std::filesystem::path& dir, const std::string& name,
                                                               const igm::IgmMesh& igm, const igm::QuadMesh& quads,
                                                               int threads) {
  create_folder(dir);
  auto out = [dir, name](const char* suffix) { return dir / (name + suffix); };
  igm::with_threads(threads, [&] {
    write_file(out(".igm.obj"), [&](std::ostream& s) { igm::write_igm_obj(s, igm, false); });
    write_file(out(".igm.exact"), [&](std::ostream& s) { igm::write_igm_obj(s, igm, true); });
    write_file(out(".quad.obj"), [&](std::ostream& s) { igm::write_quad_obj(s, quads); });
    write_file(out(".quad.svg"), [&](std::ostream& s) { igm::write_quad_svg(s, quads); });
  });
  return out;
}

// The surfaces the floor raised (PipelineOptions: the least quads of a manifold quad mesh), if any:
// one line with the total against the count asked, the first few surfaces named.
void print_floor(const igm::SurfacesResult& r) {
  std::string named;
  std::size_t raised = 0;
  for (std::size_t c = 0; c < r.components.size(); ++c) {
    const igm::PipelineStats& st = r.components[c].stats;
    if (!st.raised_by_floor()) continue;
    if (++raised <= 5) named += std::string(named.empty() ? "" : "; ") + "surface " + std::to_string(c) + " " + igm::floor_note(st);
  }
  if (raised == 0) return;
  if (raised > 5) named += "; " + std::to_string(raised - 5) + " more";
  std::printf("[sizing  ] %lld quads in all", static_cast<long long>(r.quads_total));
  if (r.quads_asked > 0) std::printf(" for %lld asked", static_cast<long long>(r.quads_asked));
  std::printf(": %s (every surface gets at least the quads its layout needs for a manifold quad mesh)\n", named.c_str());
}

// Several surfaces or open ones (igm::compute_igms): one output with all of them, the certificate
// listing each surface.
int run_surfaces(const igm::SurfaceSet& set, const std::string& name, const std::filesystem::path& dir,
                 const igm::PipelineOptions& base) {
  for (const std::string& w : set.warnings) std::printf("warning: %s\n", w.c_str());
  std::printf("[input]    %s: %zu surface%s\n", name.c_str(), set.components.size(), set.components.size() == 1 ? "" : "s");
  for (std::size_t c = 0; c < set.components.size(); ++c) {
    const igm::SurfaceComponent& comp = set.components[c];
    std::printf("[input]    surface %zu: %zu vertices, %zu faces, genus %d, %zu boundary loop%s\n", c,
                comp.positions.size(), comp.triangles.size(), comp.genus, comp.boundary_loops.size(),
                comp.boundary_loops.size() == 1 ? "" : "s");
  }
  std::fflush(stdout);
  const igm::PipelineOptions options = with_progress(base);
  const auto t0 = std::chrono::steady_clock::now();
  const igm::SurfacesResult r = igm::compute_igms(set, options);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto out = write_outputs(dir, name, r.igm, r.quads, options.threads);
  write_file(out(".cert.json"), [&](std::ostream& s) {
    s << "{\n\"input\": {\"name\": \"" << json_escape(name) << "\", \"surfaces\": " << set.components.size() << "},\n"
      << "\"certified\": " << (r.certified() ? "true" : "false") << ",\n\"surfaces\": [";
    for (std::size_t c = 0; c < r.components.size(); ++c) {
      const igm::PipelineResult& rc = r.components[c];
      s << (c ? ",\n  " : "\n  ") << "{\"vertices\": " << set.components[c].positions.size()
        << ", \"faces\": " << set.components[c].triangles.size() << ", \"genus\": " << set.components[c].genus
        << ", \"boundary_loops\": " << set.components[c].boundary_loops.size()
        << ", \"certified\": " << (rc.certified() ? "true" : "false") << ", \"quads\": " << rc.stats.quads
        << ", \"layout_quads\": " << rc.stats.layout_quads << ", \"floor_quads\": " << rc.stats.floor_quads
        << ", \"raised_by_floor\": " << (rc.stats.raised_by_floor() ? "true" : "false") << ", \"layout\": \"" << rc.stats.layout
        << "\", \"layout_fallback\": " << fallback_json(rc.stats) << ", \"stages\": " << stages_json(rc.stats) << "}";
    }
    s << "],\n\"stats\": {\"quads\": " << r.quads.quads.size() << ", \"quads_asked\": " << r.quads_asked
      << ", \"seconds\": " << total << ", \"surfaces\": [";
    for (std::size_t c = 0; c < r.components.size(); ++c)
      s << (c ? ", " : "") << "{\"layout\": \"" << r.components[c].stats.layout
        << "\", \"layout_fallback\": " << fallback_json(r.components[c].stats) << ", \"field\": " << field_json(r.components[c].stats) << "}";
    s << "]},\n"
      << "\"quality\": {\"igm\": " << igm::to_json(r.igm_quality) << ", \"quads\": " << igm::to_json(r.quad_quality)
      << ", \"features\": " << igm::to_json(r.feature_quality) << "},\n"
      << "\"igm\": " << igm::certify::to_json(r.igm_report) << ",\n"
      << "\"quad\": " << igm::certify::to_json(r.quad_report) << "}\n";
  });
  print_floor(r);
  if (base.quality)
    std::printf("[quality ] all surfaces: %s; %s\n", igm::summary_line(r.igm_quality, r.quad_quality).c_str(),
                igm::summary_line(r.feature_quality).c_str());
  std::vector<const igm::PipelineStats*> runs;
  for (const igm::PipelineResult& rc : r.components) runs.push_back(&rc.stats);
  std::printf("[total]    %8.3f s  peak memory %.0f MB\n", total, peak_rss_mb(runs));
  std::printf("wrote %s/%s.{igm.obj,igm.exact,quad.obj,cert.json,quad.svg}\n", dir.string().c_str(), name.c_str());
  return print_verdict(r.igm_report, r.quad_report);
}

int run_pipeline(const igm::ValidMesh& mesh, const std::string& name, const std::filesystem::path& dir,
                 const igm::PipelineOptions& base) {
  for (const std::string& w : mesh.warnings) std::printf("warning: %s\n", w.c_str());
  std::printf("[input]    %s: %d vertices, %d faces, genus %d\n", name.c_str(), mesh.mesh.num_vertices(),
              mesh.mesh.num_faces(), mesh.genus);
  std::fflush(stdout);
  igm::PipelineOptions options = with_progress(base);
  const auto t0 = std::chrono::steady_clock::now();
  igm::PipelineResult r = igm::compute_igm(mesh, options);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const auto out = write_outputs(dir, name, r.igm, r.quads, options.threads);
  write_file(out(".schema.svg"), [&](std::ostream& s) { igm::write_schema_svg(s, r.schema); });
  write_file(out(".cert.json"), [&](std::ostream& s) {
    const igm::PipelineStats& st = r.stats;
    s << "{\n\"input\": {\"name\": \"" << json_escape(name) << "\", \"vertices\": " << st.input_vertices
      << ", \"faces\": " << st.input_faces << ", \"genus\": " << st.genus << "},\n"
      << "\"certified\": " << (r.certified() ? "true" : "false") << ",\n"
      << "\"stats\": {\"refined_vertices\": " << st.refined_vertices << ", \"output_triangles\": " << st.output_triangles
      << ", \"layout\": \"" << st.layout << "\", \"layout_fallback\": " << fallback_json(st)
      << ", \"field\": " << field_json(st)
      << ", \"map\": \"" << igm::to_string(options.patch_map) << "\""
      << ", \"layout_quads\": " << st.layout_quads << ", \"chords\": " << st.chords << ", \"quads\": " << st.quads
      << ", \"edge_length\": " << st.edge_length << ", \"floor_quads\": " << st.floor_quads
      << ", \"quads_asked\": " << st.quads_asked << ", \"raised_by_floor\": " << (st.raised_by_floor() ? "true" : "false")
      << ", \"max_uv_bits\": " << st.max_uv_bits << ", \"tutte_iterations\": " << st.tutte.iterations
      << ", \"tutte_flips_double\": " << st.tutte.flips_double << ", \"smooth_iterations\": " << st.smooth.iterations
      << ", \"smooth_stop\": \"" << (options.smooth ? igm::to_string(st.smooth.stop) : "off") << "\""
      << ", \"seconds\": " << total << ", \"peak_mb\": " << peak_rss_mb({&st})
      << ", \"stages\": " << stages_json(st) << "},\n"
      << (st.layout == "orbifold" ? "\"genus0\": {\"cones\": [" + std::to_string(st.cones[0]) + ", " + std::to_string(st.cones[1]) +
                              ", " + std::to_string(st.cones[2]) + ", " + std::to_string(st.cones[3]) +
                              "], \"path_edges\": " + std::to_string(st.sphere_cut.path_edges) +
                              ", \"refinement_iterations\": " + std::to_string(st.orbifold.refinement.iterations) +
                              ", \"flips_double\": " + std::to_string(st.orbifold.refinement.flips_double) +
                              ", \"exact_fallback\": " + (st.orbifold.refinement.exact_fallback ? "true" : "false") +
                              "},\n"
                        : std::string())
      << "\"quality\": {\"igm\": " << igm::to_json(r.igm_quality) << ", \"quads\": " << igm::to_json(r.quad_quality)
      << ", \"features\": " << igm::to_json(r.feature_quality) << "},\n"
      << "\"igm\": " << igm::certify::to_json(r.igm_report) << ",\n"
      << "\"quad\": " << igm::certify::to_json(r.quad_report) << "}\n";
  });
  if (base.quality) std::printf("[features] %s\n", igm::summary_line(r.feature_quality).c_str());
  std::printf("[total]    %8.3f s  peak memory %.0f MB\n", total, peak_rss_mb({&r.stats}));
  std::printf("wrote %s/%s.{igm.obj,igm.exact,quad.obj,cert.json,schema.svg,quad.svg}\n", dir.string().c_str(),
              name.c_str());
  return print_verdict(r.igm_report, r.quad_report);
}

}  // namespace

int run_command(const std::vector<std::string_view>& args) {
  std::string mesh_path;
  std::filesystem::path dir = "out";
  igm::PipelineOptions options;
  bool split_nonmanifold = false;
  std::string features_path;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string_view a = args[i];
    if (a == "--help" || a == "-h") return usage("", true);
    if (a == "--cones") {
      if (i + 1 >= args.size()) return usage("--cones needs a value");
      const std::string_view v = args[++i];
      options.cones.clear();
      std::size_t start = 0;
      while (true) {  // bound: one entry per comma
        const std::size_t comma = v.find(',', start);
        const std::string_view item = v.substr(start, comma == std::string_view::npos ? v.npos : comma - start);
        long long n = 0;
        if (!parse_int(item, n) || n < INT32_MIN || n > INT32_MAX)
          return usage("--cones needs comma-separated vertex ids, got '" + std::string(v) + "'");
        options.cones.push_back(static_cast<int>(n));
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
      continue;
    }
    if (a == "--feature-angle") {
      if (i + 1 >= args.size()) return usage("--feature-angle needs a value");
      const std::string_view v = args[++i];
      double d = 0;
      if (!parse_double(v, d) || !(d >= 0 && d <= 180))
        return usage("--feature-angle needs a number of degrees in [0, 180], got '" + std::string(v) + "'");
      options.features.angle_degrees = d;
      continue;
    }
    if (a == "--feature-min-quads") {
      if (i + 1 >= args.size()) return usage("--feature-min-quads needs a value");
      const std::string_view v = args[++i];
      double d = 0;
      if (!parse_double(v, d) || !(d >= 0 && d <= 1e6))
        return usage("--feature-min-quads needs a number of quad edges in [0, 1e6], got '" + std::string(v) + "'");
      options.features.min_quad_edges = d;
      continue;
    }
    if (a == "--features") {
      if (i + 1 >= args.size()) return usage("--features needs a file");
      features_path = std::string(args[++i]);
      continue;
    }
    if (a == "--no-features") {
      options.features.enabled = false;
      continue;
    }
    if (a == "--field-alignment") {
      if (i + 1 >= args.size()) return usage("--field-alignment needs a value");
      const std::string_view v = args[++i];
      double w = 0;
      if (!parse_double(v, w) || !(w >= 0) || !std::isfinite(w))
        return usage("--field-alignment needs a number >= 0 (0: the smoothest field), got '" + std::string(v) + "'");
      options.field.alignment = w;
      options.field_attempts.clear();
      continue;
    }
    if (a == "--layout" || a == "--map" || a == "--edge-length" || a == "--smooth-seconds" ||
        a == "--smooth-min-decrease") {
      if (i + 1 >= args.size()) return usage(std::string(a) + " needs a value");
      const std::string_view v = args[++i];
      if (a == "--layout") {
        if (v == "spread") options.layout = igm::LayoutKind::Spread;
        else if (v == "kite") options.layout = igm::LayoutKind::Kite;
        else if (v == "paper") options.layout = igm::LayoutKind::Paper;
        else if (v == "field") options.layout = igm::LayoutKind::Field;
        else return usage("--layout must be field, spread, kite or paper, got '" + std::string(v) + "'");
      } else if (a == "--map") {
        if (v == "tutte") options.patch_map = igm::PatchMapKind::Tutte;
        else if (v == "affine") options.patch_map = igm::PatchMapKind::Affine;
        else return usage("--map must be tutte or affine, got '" + std::string(v) + "'");
      } else if (a == "--smooth-seconds") {
        double t = 0;
        if (!parse_double(v, t) || !(t >= 0) || !std::isfinite(t))
          return usage("--smooth-seconds needs a number >= 0 (0: no time limit), got '" + std::string(v) + "'");
        options.smooth_seconds = t;
      } else if (a == "--smooth-min-decrease") {
        double x = 0;
        if (!parse_double(v, x) || !(x >= 0 && x < 1))
          return usage("--smooth-min-decrease needs a number in [0, 1), got '" + std::string(v) + "'");
        options.smooth_min_decrease = x;
      } else {
        double h = 0;
        if (!parse_double(v, h) || !(h > 0) || !std::isfinite(h))
          return usage("--edge-length needs a positive number, got '" + std::string(v) + "'");
        options.edge_length = h;
      }
      continue;
    }
    if (a == "-o" || a == "--resolution" || a == "--root" || a == "--memory-limit-mb" || a == "--restarts" ||
        a == "--quads" || a == "--smooth-iterations" || a == "--threads") {
      if (i + 1 >= args.size()) return usage(std::string(a) + " needs a value");
      const std::string_view v = args[++i];
      if (a == "-o") {
        dir = std::string(v);
        continue;
      }
      if (a == "--restarts" && v == "auto") {
        options.restarts = -1;  // CutOptions::restarts' automatic count
        continue;
      }
      long long n = 0;
      if (!parse_int(v, n)) return usage(std::string(a) + " needs an integer, got '" + std::string(v) + "'");
      if (a == "--resolution") {
        if (n < 1 || n > 1024) return usage("--resolution must be in 1..1024");
        options.resolution = static_cast<int>(n);
      } else if (a == "--smooth-iterations") {
        if (n < 0 || n > 100000) return usage("--smooth-iterations must be in 0..100000");
        options.smooth_iterations = static_cast<int>(n);
        options.smooth_work = 0;  // the count asked for, whatever the size
      } else if (a == "--threads") {
        if (n < 0 || n > 4096) return usage("--threads must be in 0..4096 (0: all cores)");
        options.threads = static_cast<int>(n);
      } else if (a == "--quads") {
        if (n < 1 || n > (1LL << 31)) return usage("--quads must be in 1..2^31");
        options.quads = n;
      } else if (a == "--restarts") {
        if (n < 0 || n > 64) return usage("--restarts must be in 0..64 or auto");
        options.restarts = static_cast<int>(n);
      } else if (a == "--memory-limit-mb") {
        if (n < 1 || n > (1LL << 40)) return usage("--memory-limit-mb must be in 1..2^40");
        options.memory_limit_bytes = static_cast<std::uint64_t>(n) << 20;
      } else {
        if (n < 0 || n > 2000000000) return usage("--root must be a vertex id >= 0");
        options.root = static_cast<int>(n);
      }
    } else if (a == "--normal-form") {
      options.normal_form = true;
    } else if (a == "--no-smooth") {
      options.smooth = false;
    } else if (a == "--split-nonmanifold") {
      split_nonmanifold = true;
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "'");
    } else {
      if (!mesh_path.empty()) return usage("run takes one mesh file");
      mesh_path = std::string(a);
    }
  }
  if (mesh_path.empty()) return usage("run needs a mesh file");
  if ((options.resolution > 0) + (options.edge_length > 0) + (options.quads > 0) > 1)
    return usage("give at most one of --quads, --edge-length and --resolution");
  if (options.restarts != 0 && !options.normal_form) return usage("--restarts needs --normal-form");
  if (!features_path.empty()) {
    try {
      options.feature_edges = igm::read_feature_edges(features_path);
    } catch (const igm::Error& e) {
      std::fprintf(stderr, "igm: %s: %s\n", features_path.c_str(), e.what());
      return kExitInput;
    }
  }
  igm::PolygonSoup soup;
  try {
    soup = igm::read_soup(std::filesystem::path(mesh_path));
  } catch (const igm::Error& e) {  // as every error of a run: "igm: MESH: KIND: MESSAGE" (igm batch reads it)
    std::string message = e.message();
    if (message.compare(0, mesh_path.size() + 2, mesh_path + ": ") == 0) message.erase(0, mesh_path.size() + 2);
    std::fprintf(stderr, "igm: %s: %s: %s\n", mesh_path.c_str(), igm::to_string(e.kind()), message.c_str());
    return e.kind() == igm::ErrorKind::Internal ? 3 : kExitInput;
  }
  try {
    const std::string name = std::filesystem::path(mesh_path).stem().string();
    igm::SurfaceOptions so;
    so.split_nonmanifold = split_nonmanifold;
    igm::SurfaceSet set;
    try {
      set = igm::validate_surfaces(soup, so);
    } catch (const igm::Error& e) {  // with how to go on, where --split-nonmanifold would help
      const std::string hint = igm::split_nonmanifold_hint(soup, so, e, "--split-nonmanifold");
      if (hint.empty()) throw;
      throw igm::Error(e.kind(), e.message() + "; " + hint, e.elements());
    }
    soup = igm::PolygonSoup{};
    if (set.components.size() != 1 || !set.components[0].boundary_loops.empty())
      return run_surfaces(set, name, dir, options);
    const igm::ValidMesh mesh = igm::to_valid_mesh(set.components[0], set.warnings);
    return run_pipeline(mesh, name, dir, options);
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: %s: %s\n", mesh_path.c_str(), e.what());
    return e.kind() == igm::ErrorKind::Internal ? 3 : kExitInput;
  }
}

int run_default() {
  std::printf("igm: no arguments: running the pipeline on a built-in generated mesh (genus 2, ~2000 faces); "
              "see `igm --help`\n");
  igm::GenerateOptions g;
  g.genus = 2;
  g.faces = 2000;
  g.seed = 1;
  try {
    const igm::ValidMesh mesh = igm::validate(igm::generate_closed_mesh(g));
    return run_pipeline(mesh, "default-genus2", "out", igm::PipelineOptions{});
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "igm: default mesh: %s\n", e.what());
    return e.kind() == igm::ErrorKind::Internal ? 3 : kExitInput;
  }
}

}  // namespace igm_cli
