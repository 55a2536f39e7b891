// libFuzzer target: the whole pipeline on a small random mesh decoded from the bytes.
//
// Bytes -> RandomMeshSpec (tests/support/random_mesh.h: genus 0..12 closed for a first byte below
// 208, else open: genus 0..5 with 1..8 boundary loops; 4..2000 target faces (open: at least what
// the generator needs for the holes), seed,
// jitter, up to 15 edge and 15 face splits, a hostile geometry, permuted order), a root, a
// resolution 3..5, the normal form on or off (flag bit 0x40), the field layout instead of the
// topological one (flag bit 0x10: the default layout, falling back to the topological one; its
// quad count is the quantization's, so only the certificates, genus and loops are checked), then up to 64 coordinate perturbations (collapse a vertex onto another, put it
// on the segment of two others, scale it by 1e300 / 1e-300, send it to +-1e308, zero it). The
// combinatorics stay those of a closed genus-g surface (or of genus g with b loops), so:
//   validate() must accept it with genus g, and compute_igm must return an output that BOTH
//   certifier reports accept, with genus g and N x N quads per layout quad (2 cells for a sphere);
//   open: validate_surfaces() must give one surface of genus g with b loops, and compute_igm on it
//   an output both reports accept in boundary mode, with that genus and those loops (the root
//   moved to the first vertex off the boundary: a boundary root is a typed error).
// Several components (flag bit 0x20): igm_test::random_surfaces (2..300 tetrahedra, boxes and
// generated surfaces of genus 0..10, closed or open, sizes up to four orders of magnitude apart;
// generated ones of up to max(50, 4000 / components) faces), the same perturbations; validate_surfaces must find every component
// with its (genus, loops) and compute_igms with 200..1000 quads shared among them (most below
// their floor) an output both reports accept in components and boundary mode.
// No igm::Error is accepted (the mesh is valid by construction; with kGenus0Certifies false only
// Unsupported for genus 0 was; with the normal form, Unsupported for its growth bound is): any igm::Error, any other exception, a rejected output, a crash
// or a hang is a finding (abort).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "igm/core/error.h"
#include "igm/mesh/validate_surfaces.h"
#include "igm/pipeline/pipeline.h"
#include "random_mesh.h"

namespace {

// Genus 0 (orbifold embedding) has landed: spheres must certify too (false: exactly Unsupported).
constexpr bool kGenus0Certifies = true;

struct Reader {  // the fuzz bytes, read front to back; past the end every read gives 0
  const std::uint8_t* p;
  std::size_t n;
  std::uint64_t get(int bytes) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) {
      v = (v << 8) | (n > 0 ? *p : 0u);
      if (n > 0) ++p, --n;
    }
    return v;
  }
};

[[noreturn]] void finding(const char* what, const igm_test::RandomMeshSpec& s, const char* detail) {
  std::fprintf(stderr, "pipeline_fuzz: %s\n  mesh: %s\n  %s\n", what, igm_test::describe(s).c_str(), detail);
  std::abort();
}

// The open branch (see the top of the file).
int run_open(const igm::PolygonSoup& soup, const igm_test::RandomMeshSpec& s, std::uint64_t root_bytes, std::uint64_t flags) {
  igm::SurfaceSet set;
  try {
    set = igm::validate_surfaces(soup);
  } catch (const igm::Error& e) {
    finding("validate_surfaces rejected an open mesh", s, e.what());
  }
  if (set.components.size() != 1 || set.components[0].genus != s.genus ||
      set.components[0].boundary_loops.size() != static_cast<std::size_t>(s.boundaries))
    finding("wrong surfaces, genus or loops from validate_surfaces", s, "");
  const igm::SurfaceComponent& c = set.components[0];
  const int nv = static_cast<int>(c.positions.size());
  std::vector<char> on_boundary(nv, 0);
  for (const auto& loop : c.boundary_loops)
    for (int v : loop) on_boundary[v] = 1;
  igm::PipelineOptions o;
  o.layout = (flags & 0x10) != 0 ? igm::LayoutKind::Field : igm::LayoutKind::Spread;
  o.resolution = 0;
  o.quads = 200 + static_cast<std::int64_t>(flags % 3) * 300;
  o.root = -1;
  if (root_bytes != 0xFFFF)
    for (int k = 0; k < nv && o.root < 0; ++k) {
      const int v = static_cast<int>((root_bytes + static_cast<std::uint64_t>(k)) % static_cast<std::uint64_t>(nv));
      if (!on_boundary[v]) o.root = v;
    }
  o.max_witnesses = 3;
  o.quality = false;
  o.smooth_iterations = 3;
  o.smooth_seconds = 0;
  try {
    const igm::PipelineResult r = igm::compute_igm(c, o);
    if (!r.igm_report.valid()) finding("open IGM rejected by the certifier", s, igm::certify::summary(r.igm_report).c_str());
    if (!r.quad_report.valid()) finding("open quads rejected by the certifier", s, igm::certify::summary(r.quad_report).c_str());
    if (r.quad_report.genus != s.genus || r.quad_report.boundary_loops != s.boundaries)
      finding("wrong genus or loops of the open quad mesh", s, "");
  } catch (const igm::Error& e) {
    finding("typed error on a valid open mesh", s, e.what());
  } catch (const std::exception& e) {
    finding("untyped exception", s, e.what());
  }
  return 0;
}

// The several-components branch (see the top of the file).
int run_surfaces(const igm::PolygonSoup& soup, const igm_test::RandomSurfaces& m, std::uint64_t flags) {
  igm_test::RandomMeshSpec none;  // for the messages: the components are in m.description
  none.genus = -1;
  igm::SurfaceSet set;
  try {
    set = igm::validate_surfaces(soup);
  } catch (const igm::Error& e) {
    finding("validate_surfaces rejected several components", none, (e.what() + ("\n" + m.description)).c_str());
  }
  std::vector<igm::certify::ComponentTopology> expected, found;
  for (const auto& t : m.topology) expected.push_back({t[0], t[1]});
  for (const igm::SurfaceComponent& c : set.components)
    found.push_back({c.genus, static_cast<std::int64_t>(c.boundary_loops.size())});
  std::sort(expected.begin(), expected.end());
  std::sort(found.begin(), found.end());
  if (found != expected) finding("wrong surfaces, genus or loops from validate_surfaces", none, m.description.c_str());
  igm::PipelineOptions o;
  o.layout = (flags & 0x10) != 0 ? igm::LayoutKind::Field : igm::LayoutKind::Spread;
  o.quads = 200 + static_cast<std::int64_t>(flags % 3) * 400;
  o.max_witnesses = 3;
  o.quality = false;
  o.smooth_iterations = 3;
  o.smooth_seconds = 0;
  try {
    const igm::SurfacesResult r = igm::compute_igms(set, o);
    for (const igm::PipelineResult& c : r.components)
      if (!c.certified() || c.stats.quads < c.stats.floor_quads)
        finding("a surface not certified among several", none,
                (igm::certify::summary(c.quad_report) + "; " + c.stats.quad_defects + "\n" + m.description).c_str());
    if (!r.igm_report.valid()) finding("merged IGM rejected by the certifier", none, igm::certify::summary(r.igm_report).c_str());
    if (!r.quad_report.valid()) finding("merged quads rejected by the certifier", none, igm::certify::summary(r.quad_report).c_str());
    found.clear();
    for (const auto& c : r.quad_report.components) found.push_back({c.genus.value_or(-1), c.boundary_loops.value_or(-1)});
    std::sort(found.begin(), found.end());
    if (found != expected) finding("wrong components of the merged quad mesh", none, m.description.c_str());
  } catch (const igm::Error& e) {
    finding("typed error on valid surfaces", none, (e.what() + ("\n" + m.description)).c_str());
  } catch (const std::exception& e) {
    finding("untyped exception", none, e.what());
  }
  return 0;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 4096) return 0;  // 18 header bytes + 64 perturbations of 5 bytes are all that is read
  Reader in{data, size};
  igm_test::RandomMeshSpec s;
  const int first = static_cast<int>(in.get(1));
  const bool open = first >= 208;  // 208 = 16 * 13: the closed genera stay uniform below it
  s.genus = open ? (first - 208) % 6 : first % 13;
  s.boundaries = open ? 1 + (first - 208) / 6 : 0;
  const std::uint64_t faces = in.get(2);
  s.faces = 4 + static_cast<std::int64_t>(faces % 1997);
  if (open) s.faces = std::max<std::int64_t>(s.faces, 200 + 250 * s.genus + 40 * s.boundaries);
  s.seed = in.get(8);
  s.geometry = static_cast<igm_test::Geometry>(in.get(1) % static_cast<unsigned>(igm_test::Geometry::Count));
  s.jitter = 0.45 * static_cast<double>(in.get(1)) / 255.0;
  s.edge_splits = static_cast<int>(in.get(1) % 16);
  s.face_splits = static_cast<int>(in.get(1) % 16);
  const std::uint64_t root_bytes = in.get(2);
  const std::uint64_t flags = in.get(1);
  s.permute = (flags & 0x80) != 0;
  const int resolution = 3 + static_cast<int>(flags % 3);

  const bool several = (flags & 0x20) != 0;
  igm_test::RandomSurfaces surfaces;
  if (several) {  // 2..300 components (the faces field), genus up to the first byte's 0..10
    const int k = 2 + static_cast<int>(faces % 299);
    surfaces = igm_test::random_surfaces(s.seed, k, first % 11, std::max(50, 4000 / k));
  }
  igm::PolygonSoup soup = several ? std::move(surfaces.soup) : open ? igm_test::random_mesh(s) : igm_test::random_closed_mesh(s);
  auto& pos = soup.positions;
  const std::size_t nv = pos.size();
  for (int k = 0; k < 64 && in.n >= 5; ++k) {  // at most 64 perturbations
    const unsigned op = static_cast<unsigned>(in.get(1));
    const std::size_t a = in.get(2) % nv, b = in.get(2) % nv, c = (b + 1) % nv;
    igm::Vec3d& q = pos[a];
    switch (op % 6) {
      case 0: q = pos[b]; break;  // coincident
      case 1: q = {0.5 * pos[b].x + 0.5 * pos[c].x, 0.5 * pos[b].y + 0.5 * pos[c].y, 0.5 * pos[b].z + 0.5 * pos[c].z}; break;
      case 2: if (std::isfinite(q.x * 1e300) && std::isfinite(q.y * 1e300) && std::isfinite(q.z * 1e300)) q = {q.x * 1e300, q.y * 1e300, q.z * 1e300}; break;
      case 3: q = {q.x * 1e-300, q.y * 1e-300, q.z * 1e-300}; break;
      case 4: q = {(op & 8) ? 1e308 : -1e308, (op & 16) ? 1e308 : -1e308, (op & 32) ? 1e308 : -1e308}; break;
      default: q = {0.0, 0.0, 0.0}; break;
    }
  }

  if (several) return run_surfaces(soup, surfaces, flags);
  if (open) return run_open(soup, s, root_bytes, flags);

  igm::ValidMesh mesh;
  try {
    mesh = igm::validate(soup);
  } catch (const igm::Error& e) {
    finding("validate rejected a closed mesh", s, e.what());
  }
  if (mesh.genus != s.genus) finding("wrong genus from validate", s, "");
  igm::PipelineOptions o;
  o.resolution = resolution;
  o.root = root_bytes == 0xFFFF ? -1 : static_cast<int>(root_bytes % static_cast<std::uint64_t>(mesh.mesh.num_vertices()));
  o.max_witnesses = 3;
  o.quality = false;
  o.smooth_iterations = 3;
  o.normal_form = (flags & 0x40) != 0;
  const bool field = (flags & 0x10) != 0 && !o.normal_form;
  o.layout = field ? igm::LayoutKind::Field : igm::LayoutKind::Spread;
  try {
    const igm::PipelineResult r = igm::compute_igm(mesh, o);
    if (s.genus == 0 && !kGenus0Certifies) finding("genus 0 accepted: set kGenus0Certifies = true", s, "");
    if (!r.igm_report.valid()) finding("IGM rejected by the certifier", s, igm::certify::summary(r.igm_report).c_str());
    if (!r.quad_report.valid()) finding("quads rejected by the certifier", s, igm::certify::summary(r.quad_report).c_str());
    // Layout quads: 2 for a sphere ([0,2] x [0,1]), else the default layout's.
    const int layout = s.genus == 0 ? 2 : igm::layout_quad_count(igm::LayoutKind::Spread, 4 * s.genus);
    if (r.igm_report.genus != s.genus || r.quad_report.genus != s.genus ||
        (!field && static_cast<int>(r.quads.quads.size()) != layout * resolution * resolution))
      finding("wrong genus or quad count", s, "");
  } catch (const igm::Error& e) {
    if (s.genus == 0 && !kGenus0Certifies && e.kind() == igm::ErrorKind::Unsupported) return 0;
    if (o.normal_form && e.kind() == igm::ErrorKind::Unsupported &&
        std::string(e.what()).find("max_normal_form_growth") != std::string::npos)
      return 0;
    finding("typed error on a valid closed mesh", s, e.what());
  } catch (const std::exception& e) {
    finding("untyped exception", s, e.what());
  }
  return 0;
}
