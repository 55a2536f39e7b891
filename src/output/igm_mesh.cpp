#include "igm/output/igm_mesh.h"

#include <cstdio>
#include <ostream>
#include <string>

#include "igm/core/error.h"

namespace igm {

namespace {

void put_double(std::ostream& out, double x) {
  char buf[32];
  int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  out.write(buf, n);
}

void put_positions(std::ostream& out, const std::vector<Vec3d>& positions) {
  for (const Vec3d& p : positions) {
    out << "v ";
    put_double(out, p.x);
    out << ' ';
    put_double(out, p.y);
    out << ' ';
    put_double(out, p.z);
    out << '\n';
  }
}

}  // namespace

void write_igm_obj(std::ostream& out, const IgmMesh& igm, bool exact) {
  if (igm.corner_uv.size() != igm.triangles.size())
    throw Error(ErrorKind::InvalidArgument, "IGM has " + std::to_string(igm.triangles.size()) + " triangles but " +
                                                std::to_string(igm.corner_uv.size()) + " UV triples");
  out << (exact ? "# igm exact IGM: one vt per face corner, exact rationals p/q\n"
                : "# igm IGM: one vt per face corner (doubles rounded from exact rationals)\n");
  put_positions(out, igm.positions);
  for (const auto& tri : igm.corner_uv)
    for (const Point2q& uv : tri) {
      out << "vt ";
      if (exact) {
        out << to_string(uv.x) << ' ' << to_string(uv.y);
      } else {
        put_double(out, to_double(uv.x));
        out << ' ';
        put_double(out, to_double(uv.y));
      }
      out << '\n';
    }
  for (std::size_t f = 0; f < igm.triangles.size(); ++f) {
    out << 'f';
    for (int i = 0; i < 3; ++i) out << ' ' << igm.triangles[f][i] + 1 << '/' << 3 * f + i + 1;
    out << '\n';
  }
}

void write_quad_obj(std::ostream& out, const QuadMesh& q) {
  out << "# igm quad mesh\n";
  put_positions(out, q.positions);
  for (const auto& f : q.quads) out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << ' ' << f[3] + 1 << '\n';
}

}  // namespace igm
