#pragma once
// Shared body of the mesh-reader fuzz targets (read_{obj,off,ply,stl}_fuzz.cpp): read_soup(bytes,
// format) then inspect and validate. Any exception other than igm::Error, a crash, or a
// disagreement between inspect() and validate() is a bug (abort). Valid meshes are also written
// as OBJ, read back and validated again (same genus).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/mesh/validate.h"

inline int fuzz_read_mesh(const std::uint8_t* data, std::size_t size, igm::MeshFormat format) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  igm::PolygonSoup soup;
  try {
    soup = igm::read_soup(bytes, format);
  } catch (const igm::Error&) {
    return 0;  // a typed error is the expected outcome for bad input
  }
  const igm::MeshReport report = igm::inspect(soup);
  try {
    const igm::ValidMesh m = igm::validate(soup);
    if (!report.problems.empty()) std::abort();  // inspect found a fatal problem validate missed
    if (!m.mesh.check_invariants().empty()) std::abort();
    const long long chi = static_cast<long long>(m.mesh.num_vertices()) - m.mesh.num_edges() + m.mesh.num_faces();
    if (m.genus != report.genus || chi != 2 - 2LL * m.genus) std::abort();
    std::vector<std::array<int, 3>> tris(static_cast<std::size_t>(m.mesh.num_faces()));
    for (int f = 0; f < m.mesh.num_faces(); ++f) tris[static_cast<std::size_t>(f)] = m.mesh.face_vertices(f);
    const igm::ValidMesh again =
        igm::validate(igm::read_soup(igm::format_obj(m.positions, tris), igm::MeshFormat::Obj));
    if (again.genus != m.genus || again.mesh.num_faces() != m.mesh.num_faces() || !again.warnings.empty()) std::abort();
  } catch (const igm::Error& e) {
    if (report.problems.empty() || e.kind() != report.problems.front().kind) std::abort();
  }
  return 0;
}
