#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/io/write_mesh.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"

using namespace igm;

namespace {
std::vector<std::array<int, 3>> tris_of(const TriMesh& m) {
  std::vector<std::array<int, 3>> t(static_cast<std::size_t>(m.num_faces()));
  for (int f = 0; f < m.num_faces(); ++f) t[static_cast<std::size_t>(f)] = m.face_vertices(f);
  return t;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST_CASE("OBJ and OFF round trip is exact (positions bit for bit, faces as written)") {
  const ValidMesh m = validate(generate_closed_mesh({.genus = 3, .faces = 800, .seed = 3}));
  std::vector<Vec3d> pos = m.positions;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> d(-1e6, 1e6);
  for (Vec3d& p : pos) p = {d(rng), d(rng) * 1e-300, std::ldexp(d(rng), -1074 + 60)};  // awkward magnitudes
  pos[0] = {-0.0, 5e-324, 1.7976931348623157e308};
  const auto tris = tris_of(m.mesh);
  for (MeshFormat fmt : {MeshFormat::Obj, MeshFormat::Off}) {
    const std::string text = fmt == MeshFormat::Obj ? format_obj(pos, tris) : format_off(pos, tris);
    const PolygonSoup s = read_soup(text, fmt);
    REQUIRE(s.positions.size() == pos.size());
    for (std::size_t v = 0; v < pos.size(); ++v) {
      CHECK(same_bits(s.positions[v].x, pos[v].x));
      CHECK(same_bits(s.positions[v].y, pos[v].y));
      CHECK(same_bits(s.positions[v].z, pos[v].z));
    }
    REQUIRE(s.num_faces() == tris.size());
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (int i = 0; i < 3; ++i) CHECK(s.corners[3 * f + i] == tris[f][i]);
    CHECK(validate(s).genus == 3);
  }
}

TEST_CASE("writers to files, and their errors") {
  const auto dir = std::filesystem::temp_directory_path() / "igm-write-test";
  std::filesystem::create_directories(dir);
  const std::vector<Vec3d> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::array<int, 3>> tris = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  write_obj(dir / "t.obj", pos, tris);
  write_off(dir / "t.off", pos, tris);
  CHECK(load_mesh(dir / "t.obj").genus == 0);
  CHECK(load_mesh(dir / "t.off").genus == 0);
  CHECK(read_file_bytes(dir / "t.obj") == format_obj(pos, tris));
  CHECK(format_obj(pos, {{0, 2, 1}}) == "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\n");
  CHECK_THROWS_AS(write_obj(dir / "no-such-dir" / "t.obj", pos, tris), Error);
  try {
    format_off(pos, {{0, 1, 4}});
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::IndexOutOfRange);
    CHECK(e.elements() == std::vector<std::int64_t>{0});
  }
  std::filesystem::remove_all(dir);
}
