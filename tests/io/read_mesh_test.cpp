#include <doctest/doctest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "certify/obj.h"
#include "igm/core/error.h"
#include "igm/io/read_mesh.h"
#include "igm/mesh/validate.h"
#include "test_data.h"

using namespace igm;

namespace {

std::vector<std::vector<std::int64_t>> faces_of(const PolygonSoup& s) {
  std::vector<std::vector<std::int64_t>> out;
  for (std::size_t f = 0; f < s.num_faces(); ++f)
    out.emplace_back(s.corners.begin() + static_cast<std::ptrdiff_t>(s.face_begin[f]),
                     s.corners.begin() + static_cast<std::ptrdiff_t>(s.face_begin[f + 1]));
  return out;
}

// Runs f, requires an igm::Error of `kind`, returns it.
template <class F>
Error error_of(F&& f, ErrorKind kind) {
  try {
    f();
  } catch (const Error& e) {
    CHECK_MESSAGE(e.kind() == kind, e.what());
    return e;
  }
  FAIL("no igm::Error thrown");
  return Error(ErrorKind::Internal, "unreachable");
}

ErrorKind kind_of_read(std::string_view bytes, MeshFormat fmt) {
  try {
    read_soup(bytes, fmt);
  } catch (const Error& e) {
    return e.kind();
  }
  return ErrorKind::Internal;  // "no error"
}

std::string to_crlf(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '\n') out.push_back('\r');
    out.push_back(c);
  }
  return out;
}

// Little helpers to build binary PLY / STL in memory.
struct Bin {
  std::string s;
  bool big = false;
  template <class T>
  void put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big == (std::endian::native == std::endian::little))
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    s.append(b, sizeof(T));
  }
};

}  // namespace

TEST_CASE("format_from_path") {
  CHECK(format_from_path("a/b.OBJ") == MeshFormat::Obj);
  CHECK(format_from_path("x.off") == MeshFormat::Off);
  CHECK(format_from_path("x.Ply") == MeshFormat::Ply);
  CHECK(format_from_path("x.stl") == MeshFormat::Stl);
  error_of([] { format_from_path("x.txt"); }, ErrorKind::Io);
  error_of([] { format_from_path("noext"); }, ErrorKind::Io);
}

TEST_CASE("files that cannot be read give Io errors") {
  error_of([] { read_soup(std::filesystem::path("/nonexistent/dir/x.obj")); }, ErrorKind::Io);
  error_of([] { read_soup(std::filesystem::temp_directory_path() / "igm-io-test-no-such-file.off"); }, ErrorKind::Io);
  const auto dir = std::filesystem::temp_directory_path() / "igm-io-test-dir.obj";
  std::filesystem::create_directories(dir);
  error_of([&] { read_soup(dir); }, ErrorKind::Io);
  std::filesystem::remove(dir);
}

TEST_CASE("OBJ: corner forms, negative indices, polygons, comments, CRLF, ignored statements") {
  const std::string text =
      "# a comment\r\n"
      "mtllib a.mtl\r\n"
      "o thing\r\n"
      "v 0 0 0\r\n"
      "v 1.5 -2e3 +3\r\n"
      "v 0 1 0 1.0\r\n"          // w is ignored
      "v 0 0 1 0.5 0.5 0.5\r\n"  // colour is ignored
      "vt 0 0\r\nvn 0 0 1\r\ng grp\r\ns 1\r\nusemtl m\r\n"
      "f 1 2 3\r\n"
      "f 1/1 2/1 4/1\r\n"
      "f 1//1 4//1 3//1 # trailing comment\r\n"
      "f -3/1/1 -2/1/1 -1/1/1 -4/1/1\r\n"  // a quad with relative indices: 2 3 4 1
      "l 1 2\r\n"
      "f 1 \\\r\n 2 3\r\n";  // continuation line
  const PolygonSoup s = read_soup(text, MeshFormat::Obj);
  REQUIRE(s.positions.size() == 4);
  CHECK(s.positions[1].x == 1.5);
  CHECK(s.positions[1].y == -2000.0);
  CHECK(s.positions[1].z == 3.0);
  CHECK(s.positions[3].z == 1.0);
  const auto f = faces_of(s);
  REQUIRE(f.size() == 5);
  CHECK(f[0] == std::vector<std::int64_t>{0, 1, 2});
  CHECK(f[1] == std::vector<std::int64_t>{0, 1, 3});
  CHECK(f[2] == std::vector<std::int64_t>{0, 3, 2});
  CHECK(f[3] == std::vector<std::int64_t>{1, 2, 3, 0});
  CHECK(f[4] == std::vector<std::int64_t>{0, 1, 2});
}

TEST_CASE("OBJ: relative indices refer to the vertices read so far") {
  const PolygonSoup s = read_soup("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -1 -2 -3\n", MeshFormat::Obj);
  const auto f = faces_of(s);
  CHECK(f[0] == std::vector<std::int64_t>{0, 1, 2});
  CHECK(f[1] == std::vector<std::int64_t>{3, 2, 1});
}

TEST_CASE("OBJ: malformed input names the line") {
  Error e = error_of([] { read_soup("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", MeshFormat::Obj); }, ErrorKind::Parse);
  CHECK(e.elements() == std::vector<std::int64_t>{4});
  CHECK(std::string(e.what()).find("line 4") != std::string::npos);
  e = error_of([] { read_soup("v 0 0\n", MeshFormat::Obj); }, ErrorKind::Parse);
  CHECK(e.elements() == std::vector<std::int64_t>{1});
  error_of([] { read_soup("v 0 0 0\nv 1 0 0\nf 1 2\n", MeshFormat::Obj); }, ErrorKind::Parse);
  error_of([] { read_soup("v 0 0 0\nf 1 2 x\n", MeshFormat::Obj); }, ErrorKind::Parse);
  error_of([] { read_soup("v 0 0 0abc\n", MeshFormat::Obj); }, ErrorKind::Parse);
  error_of([] { read_soup("v 0 0 0\nf 1 2 99999999999999999999999\n", MeshFormat::Obj); }, ErrorKind::Parse);
  // Out-of-range ids are syntax-correct: kept for validation to report.
  const PolygonSoup s = read_soup("v 0 0 0\nf 1 2 -7\n", MeshFormat::Obj);
  CHECK(faces_of(s)[0] == std::vector<std::int64_t>{0, 1, -6});
  CHECK(inspect(s).problems.front().kind == ErrorKind::IndexOutOfRange);
}

TEST_CASE("OFF: header variants, comments, blank lines, colours") {
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const std::string head : {"OFF\n4 4 6\n", "OFF 4 4 6\n", "OFF\n4 4\n", "# c\n\nOFF\n# c2\n4 4 0\n\n", "4 4 0\n",
                                 "OFF\r\n4 4 6\r\n", "nOFF\n3\n4 4 0\n"}) {
    CAPTURE(head);
    const PolygonSoup s = read_soup(head + body, MeshFormat::Off);
    CHECK(s.positions.size() == 4);
    CHECK(s.num_faces() == 4);
    CHECK(faces_of(s)[3] == std::vector<std::int64_t>{1, 2, 3});
  }
  const PolygonSoup c = read_soup(
      "COFF\n4 4 0\n0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n0 1 0 1 1 1 1\n0 0 1 0 0 0 0\n"
      "3 0 2 1 0.5 0.5 0.5\n3 0 1 3\n3 0 3 2 1 2 3 4\n3 1 2 3\n",
      MeshFormat::Off);
  CHECK(c.positions[1].x == 1.0);
  CHECK(c.positions[2].y == 1.0);
  CHECK(faces_of(c)[2] == std::vector<std::int64_t>{0, 3, 2});
  const PolygonSoup n = read_soup("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n", MeshFormat::Off);
  CHECK(n.positions[2].y == 1.0);
  const PolygonSoup st = read_soup("STOFF\n3 1 0\n0 0 0 0.5 0.5\n1 0 0 1 1\n0 1 0 0 0\n4 0 1 2 1\n", MeshFormat::Off);
  CHECK(faces_of(st)[0].size() == 4);
}

TEST_CASE("OFF: errors") {
  CHECK(kind_of_read("", MeshFormat::Off) == ErrorKind::Parse);
  CHECK(kind_of_read("PLY\n", MeshFormat::Off) == ErrorKind::Parse);
  CHECK(kind_of_read("4OFF\n1 0 0\n0 0 0 0\n", MeshFormat::Off) == ErrorKind::Unsupported);
  CHECK(kind_of_read("OFF BINARY\n", MeshFormat::Off) == ErrorKind::Unsupported);
  CHECK(kind_of_read("nOFF\n2\n1 0 0\n0 0\n", MeshFormat::Off) == ErrorKind::Unsupported);
  CHECK(kind_of_read("OFF\n-1 0 0\n", MeshFormat::Off) == ErrorKind::Parse);
  // Declared counts beyond the bytes: rejected before reserving anything.
  CHECK(kind_of_read("OFF\n1000000000000 1 0\n0 0 0\n", MeshFormat::Off) == ErrorKind::TooLarge);
  CHECK(kind_of_read("OFF\n1 1000000000000 0\n0 0 0\n", MeshFormat::Off) == ErrorKind::TooLarge);
  // Truncated in the middle of a face: names the face and the line.
  Error e = error_of([] { read_soup("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1\n", MeshFormat::Off); },
                     ErrorKind::Parse);
  CHECK(std::string(e.what()).find("face 1") != std::string::npos);
  error_of([] { read_soup("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", MeshFormat::Off); }, ErrorKind::Parse);
  error_of([] { read_soup("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", MeshFormat::Off); }, ErrorKind::Parse);
  error_of([] { read_soup("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000000 0 1 2\n", MeshFormat::Off); },
           ErrorKind::Parse);
}

namespace {
// A PLY with a leading junk element, extra vertex and face properties, a trailing element.
std::string make_ply(const char* format, const char* vtype, const char* ctype, const char* itype, bool big,
                     bool binary) {
  std::string h = std::string("ply\nformat ") + format + " 1.0\ncomment made by a test\nobj_info x\n" +
                  "element junk 2\nproperty uchar a\nproperty list uchar float b\n" + "element vertex 4\nproperty " +
                  vtype + " x\nproperty " + vtype + " y\nproperty uchar red\nproperty " + vtype + " z\n" +
                  "property list ushort int extra\n" + "element face 4\nproperty float q\nproperty list " + ctype +
                  " " + itype + " vertex_indices\n" + "element edge 1\nproperty int v1\nproperty int v2\nend_header\n";
  const double pos[4][3] = {{0, 0, 0}, {1.5, 0, 0}, {0, 1, 0}, {0, 0, -2}};
  const int faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  if (!binary) {
    std::string b = "1 2 0.5 0.25\n7 0\n";
    for (auto& p : pos)
      b += std::to_string(p[0]) + " " + std::to_string(p[1]) + " 9 " + std::to_string(p[2]) + " 2 5 6\n";
    for (auto& f : faces)
      b += "0.5 3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    return h + b + "0 1\n";
  }
  Bin b;
  b.big = big;
  auto put_num = [&](const std::string& type, double v) {
    if (type == "float" || type == "float32")
      b.put(static_cast<float>(v));
    else if (type == "double" || type == "float64")
      b.put(v);
    else if (type == "char" || type == "int8")
      b.put(static_cast<std::int8_t>(v));
    else if (type == "uchar" || type == "uint8")
      b.put(static_cast<std::uint8_t>(v));
    else if (type == "short" || type == "int16")
      b.put(static_cast<std::int16_t>(v));
    else if (type == "ushort" || type == "uint16")
      b.put(static_cast<std::uint16_t>(v));
    else if (type == "int" || type == "int32")
      b.put(static_cast<std::int32_t>(v));
    else if (type == "uint" || type == "uint32")
      b.put(static_cast<std::uint32_t>(v));
    else
      FAIL("bad type");
  };
  b.put(std::uint8_t{1}), b.put(std::uint8_t{2}), b.put(0.5f), b.put(0.25f);
  b.put(std::uint8_t{7}), b.put(std::uint8_t{0});
  for (auto& p : pos) {
    put_num(vtype, p[0]), put_num(vtype, p[1]), b.put(std::uint8_t{9}), put_num(vtype, p[2]);
    b.put(std::uint16_t{2}), b.put(std::int32_t{5}), b.put(std::int32_t{6});
  }
  for (auto& f : faces) {
    b.put(0.5f);
    put_num(ctype, 3);
    for (int v : f) put_num(itype, v);
  }
  b.put(std::int32_t{0}), b.put(std::int32_t{1});
  return h + b.s;
}

void check_ply_tetra(const PolygonSoup& s, bool integer_coords) {
  REQUIRE(s.positions.size() == 4);
  CHECK(s.positions[1].x == (integer_coords ? 1.0 : 1.5));
  CHECK(s.positions[3].z == -2.0);
  CHECK(s.positions[2].y == 1.0);
  const auto f = faces_of(s);
  REQUIRE(f.size() == 4);
  CHECK(f[0] == std::vector<std::int64_t>{0, 2, 1});
  CHECK(f[3] == std::vector<std::int64_t>{1, 2, 3});
  CHECK(validate(s).genus == 0);
}
}  // namespace

TEST_CASE("PLY: ascii and binary, every type, extra properties and elements skipped") {
  check_ply_tetra(read_soup(make_ply("ascii", "float", "uchar", "int", false, false), MeshFormat::Ply), false);
  const char* coord_types[] = {"float", "double", "float32", "float64", "char",
                               "short", "int",    "int8",    "int16",   "int32"};
  const char* count_types[] = {"uchar", "char", "ushort", "short", "int", "uint", "uint8", "int32", "uint32"};
  const char* index_types[] = {"int",  "uint",  "uchar", "char",   "short", "ushort",
                               "int8", "uint8", "int16", "uint16", "int32", "uint32"};
  for (bool big : {false, true}) {
    const char* fmt = big ? "binary_big_endian" : "binary_little_endian";
    for (const char* vt : coord_types) {
      CAPTURE(vt);
      const std::string ply = make_ply(fmt, vt, "uchar", "int", big, true);
      const bool integral =
          std::string(vt).find("int") != std::string::npos || std::string(vt) == "char" || std::string(vt) == "short";
      check_ply_tetra(read_soup(ply, MeshFormat::Ply), integral);
    }
    for (const char* ct : count_types)
      for (const char* it : index_types) {
        CAPTURE(ct);
        CAPTURE(it);
        check_ply_tetra(read_soup(make_ply(fmt, "double", ct, it, big, true), MeshFormat::Ply), false);
      }
  }
  // \r\n header lines
  check_ply_tetra(read_soup(to_crlf(make_ply("ascii", "float", "uchar", "int", false, false)), MeshFormat::Ply), false);
}

TEST_CASE("PLY: declared counts are checked against the bytes before allocating") {
  const std::string head =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n";
  Error e = error_of([&] { read_soup(head + std::string(64, '\0'), MeshFormat::Ply); }, ErrorKind::TooLarge);
  CHECK(std::string(e.what()).find("1000000000000") != std::string::npos);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nelement vertex 1000000000000\nproperty float x\nproperty float "
                     "y\nproperty float z\nend_header\n0 0 0\n",
                     MeshFormat::Ply) == ErrorKind::TooLarge);
  // An element without properties costs nothing to skip, whatever its count.
  const PolygonSoup s = read_soup(
      "ply\nformat binary_little_endian 1.0\nelement nothing 1000000000000\nelement vertex 0\nproperty float x\n"
      "property float y\nproperty float z\nend_header\n",
      MeshFormat::Ply);
  CHECK(s.positions.empty());
  // A list longer than the file.
  Bin b;
  b.put(0.f), b.put(0.f), b.put(0.f);
  b.put(std::uint32_t{1000000000});
  CHECK(kind_of_read("ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n" +
                         b.s,
                     MeshFormat::Ply) == ErrorKind::TooLarge);
  // Truncated binary body.
  const std::string full = make_ply("binary_little_endian", "float", "uchar", "int", false, true);
  for (std::size_t cut : {full.size() - 1, full.size() - 9, full.size() - 30, full.find("end_header") + 11})
    CHECK(kind_of_read(full.substr(0, cut), MeshFormat::Ply) != ErrorKind::Internal);
}

TEST_CASE("PLY: header errors") {
  CHECK(kind_of_read("", MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", MeshFormat::Ply) ==
        ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 2.0\nend_header\n", MeshFormat::Ply) == ErrorKind::Unsupported);
  CHECK(kind_of_read("ply\nformat weird 1.0\nend_header\n", MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nproperty float x\nend_header\n", MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
                     MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read(
            "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n3 0 1 2\n",
            MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read(
            "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n3 0 1 2\n",
            MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                     "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0 2 0 1\n",
                     MeshFormat::Ply) == ErrorKind::Parse);
}

namespace {
std::string stl_binary(const std::vector<std::array<Vec3d, 3>>& tris, const std::string& header) {
  Bin b;
  b.s = header;
  b.s.resize(80, ' ');
  b.put(static_cast<std::uint32_t>(tris.size()));
  for (const auto& t : tris) {
    b.put(0.f), b.put(0.f), b.put(1.f);
    for (const Vec3d& p : t)
      b.put(static_cast<float>(p.x)), b.put(static_cast<float>(p.y)), b.put(static_cast<float>(p.z));
    b.put(std::uint16_t{0});
  }
  return b.s;
}
std::string stl_ascii(const std::vector<std::array<Vec3d, 3>>& tris) {
  std::string s = "solid t\n";
  for (const auto& t : tris) {
    s += " facet normal 0 0 1\n  outer loop\n";
    for (const Vec3d& p : t)
      s += "   vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    s += "  endloop\n endfacet\n";
  }
  return s + "endsolid t\n";
}
std::vector<std::array<Vec3d, 3>> tetra_tris() {
  const Vec3d p[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::vector<std::array<Vec3d, 3>> t;
  for (auto& x : f) t.push_back({p[x[0]], p[x[1]], p[x[2]]});
  return t;
}
}  // namespace

TEST_CASE("STL: binary (also with a 'solid' header) and ascii, welded") {
  for (const std::string& bytes : {stl_binary(tetra_tris(), "binary"),
                                   stl_binary(tetra_tris(), "solid looks like ascii"), stl_ascii(tetra_tris())}) {
    const PolygonSoup s = read_soup(bytes, MeshFormat::Stl);
    CHECK(s.positions.size() == 4);  // 12 corners welded into 4 vertices
    CHECK(s.num_faces() == 4);
    CHECK(faces_of(s)[0] == std::vector<std::int64_t>{0, 1, 2});
    const ValidMesh m = validate(s);
    CHECK(m.genus == 0);
    CHECK(m.warnings.empty());
  }
  // -0 and +0 weld; positions that differ in the last bit do not.
  auto t = tetra_tris();
  t[1][0].x = -0.0;
  CHECK(read_soup(stl_binary(t, "x"), MeshFormat::Stl).positions.size() == 4);
  t[1][0].x = std::nextafter(0.0f, 1.0f);
  CHECK(read_soup(stl_binary(t, "x"), MeshFormat::Stl).positions.size() == 5);
  CHECK(read_soup(to_crlf(stl_ascii(tetra_tris())), MeshFormat::Stl).positions.size() == 4);
  // A non-ASCII solid name does not make an ascii file binary.
  std::string named = stl_ascii(tetra_tris());
  named.replace(0, 7, "solid caf\xc3\xa9\n");
  CHECK(read_soup(named, MeshFormat::Stl).positions.size() == 4);
}

TEST_CASE("STL: errors") {
  const std::string bin = stl_binary(tetra_tris(), "binary");
  CHECK(kind_of_read(bin.substr(0, bin.size() - 1), MeshFormat::Stl) == ErrorKind::TooLarge);
  CHECK(kind_of_read(bin + "x", MeshFormat::Stl) == ErrorKind::Parse);
  CHECK(kind_of_read("abc", MeshFormat::Stl) == ErrorKind::Parse);
  // A truncated binary file whose header starts with "solid": a binary size error, not ascii noise.
  const std::string solid_bin = stl_binary(tetra_tris(), "solid binary");
  CHECK(kind_of_read(solid_bin.substr(0, solid_bin.size() - 7), MeshFormat::Stl) == ErrorKind::TooLarge);
  CHECK(kind_of_read("", MeshFormat::Stl) == ErrorKind::Parse);
  std::string huge = bin.substr(0, 84);
  huge[80] = huge[81] = huge[82] = huge[83] = '\xff';
  CHECK(kind_of_read(huge, MeshFormat::Stl) == ErrorKind::TooLarge);
  const std::string asc = stl_ascii(tetra_tris());
  CHECK(kind_of_read(asc.substr(0, asc.size() / 2), MeshFormat::Stl) == ErrorKind::Parse);
  CHECK(
      kind_of_read("solid x\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
                   MeshFormat::Stl) == ErrorKind::Parse);
  CHECK(kind_of_read("solid x\nvertex 0 0 0\nendsolid\n", MeshFormat::Stl) == ErrorKind::Parse);
}

// Regression (issue 40): admesh's examples/block.stl, an ascii STL in capitals ("SOLID",
// "FACET NORMAL", ...) whose bytes 80-83 are spaces, was taken for a broken binary file that
// declares 0x20202020 = 538,976,288 triangles (too_large). The smallest such file: a tetrahedron
// written the same way.
TEST_CASE("STL: ascii in capitals is ascii, decided by content") {
  std::string caps = "SOLID Untitled1\n";
  for (const auto& t : tetra_tris()) {
    caps += " FACET NORMAL  0.00000000E+00  0.00000000E+00  1.00000000E+00\n      OUTER LOOP\n";
    for (const Vec3d& p : t)
      caps += "      VERTEX  " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    caps += "    ENDLOOP\n ENDFACET\n";
  }
  caps += "ENDSOLID Untitled1\n";
  REQUIRE(caps.substr(80, 4) == "    ");  // the binary count field reads 538,976,288
  const PolygonSoup s = read_soup(caps, MeshFormat::Stl);
  CHECK(s.positions.size() == 4);
  CHECK(s.num_faces() == 4);
  CHECK(faces_of(s)[3] == std::vector<std::int64_t>{2, 1, 3});  // ids by first appearance
  CHECK(validate(s).genus == 0);
  // Mixed case too (keywords are case-insensitive), with CRLF.
  std::string mixed = stl_ascii(tetra_tris());
  mixed.replace(0, 5, "Solid");
  mixed.replace(mixed.find("outer loop"), 10, "Outer Loop");
  mixed.replace(mixed.find("vertex"), 6, "Vertex");
  CHECK(read_soup(to_crlf(mixed), MeshFormat::Stl).num_faces() == 4);
  // Still binary: a binary file whose 80-byte header starts with "SOLID" and whose size matches.
  const std::string caps_bin = stl_binary(tetra_tris(), "SOLID binary in capitals");
  CHECK(read_soup(caps_bin, MeshFormat::Stl).positions.size() == 4);
  // Still refused: that binary file truncated (a size error, not ascii noise), a header word
  // that only starts with "solid", an unknown keyword.
  CHECK(kind_of_read(caps_bin.substr(0, caps_bin.size() - 7), MeshFormat::Stl) == ErrorKind::TooLarge);
  const std::string works_bin = stl_binary(tetra_tris(), "solidworks export");
  CHECK(kind_of_read(works_bin.substr(0, works_bin.size() - 7), MeshFormat::Stl) == ErrorKind::TooLarge);
  CHECK(kind_of_read("SOLIDX\nENDSOLID\n", MeshFormat::Stl) == ErrorKind::Parse);
  std::string bad = caps;
  bad.replace(bad.find("ENDLOOP"), 7, "ENDLOOQ");
  CHECK(kind_of_read(bad, MeshFormat::Stl) == ErrorKind::Parse);
}

// Regression (issue 40): a PLY whose header has a line a writer added without the `comment`
// keyword (Blender 2.47's "Created by ...") was refused as an unknown keyword. Such a line
// declares nothing: it is skipped with a warning that names it; validation passes it on.
TEST_CASE("PLY: unknown header lines are skipped with a warning") {
  const std::string body = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  const std::string tail =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string ply = "ply\nformat ascii 1.0\nCreated by Blender 2.47 - www.blender.org\n" + tail + body;
  const PolygonSoup s = read_soup(ply, MeshFormat::Ply);
  CHECK(s.num_faces() == 4);
  REQUIRE(s.warnings.size() == 1);
  CHECK(s.warnings[0] == "PLY header line 3 skipped (unknown keyword 'Created')");
  const ValidMesh m = validate(s);
  CHECK(m.genus == 0);
  CHECK(m.warnings == s.warnings);
  CHECK(inspect(s).warnings == s.warnings);
  // comment and obj_info lines are the format's own: no warning.
  CHECK(read_soup("ply\nformat ascii 1.0\ncomment x\nobj_info y\n" + tail + body, MeshFormat::Ply).warnings.empty());
  // In a binary file too, and with CRLF header lines (the line number counts physical lines).
  Bin b;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f}) b.put(v);
  const int tris[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const auto& t : tris) {
    b.put(std::uint8_t{3});
    for (int v : t) b.put(std::int32_t{v});
  }
  const std::string bin =
      to_crlf("ply\nformat binary_little_endian 1.0\ncomment ok\nexported by someone\n" + tail) + b.s;
  const PolygonSoup sb = read_soup(bin, MeshFormat::Ply);
  CHECK(sb.num_faces() == 4);
  REQUIRE(sb.warnings.size() == 1);
  CHECK(sb.warnings[0] == "PLY header line 4 skipped (unknown keyword 'exported')");
  // Many unknown lines: ten warnings name their lines, one counts the rest.
  std::string many = "ply\nformat ascii 1.0\n";
  for (int i = 0; i < 25; ++i) many += "junk line\n";
  const PolygonSoup sm = read_soup(many + tail + body, MeshFormat::Ply);
  REQUIRE(sm.warnings.size() == 11);
  CHECK(sm.warnings[9] == "PLY header line 12 skipped (unknown keyword 'junk')");
  CHECK(sm.warnings[10] == "15 more unknown PLY header lines skipped");
  // Still refused: a structural keyword in other than lower case (skipping it would change the
  // layout), a misspelt property type, a header without end_header.
  std::string upper = "ply\nformat ascii 1.0\n" + tail + body;
  upper.replace(upper.find("property float z"), 8, "PROPERTY");
  Error e = error_of([&] { read_soup(upper, MeshFormat::Ply); }, ErrorKind::Parse);
  CHECK(e.elements() == std::vector<std::int64_t>{6});
  std::string typo = "ply\nformat ascii 1.0\n" + tail + body;
  typo.replace(typo.find("float z"), 5, "flaot");
  CHECK(kind_of_read(typo, MeshFormat::Ply) == ErrorKind::Parse);
  CHECK(kind_of_read("ply\nformat ascii 1.0\nCreated by me\n", MeshFormat::Ply) == ErrorKind::Parse);
}

// Regression (issue 40): backslash continuations, also before CRLF, were refused by the
// certifier's OBJ reader; both OBJ readers must read the same faces from such a file.
TEST_CASE("OBJ: continuations read alike by this reader and the certifier's") {
  for (const std::string eol : {"\n", "\r\n"}) {
    CAPTURE(eol.size());
    const std::string text = "v 0 0 0" + eol + "v 1 0 0 \\" + eol + "# a comment ends its line \\" + eol +
                             "v 0 1 0" + eol + "v 0 0 1" + eol + "f 1 3 \\" + eol + " 2" + eol + "f 1 2\\ " + eol +
                             "4" + eol + "f 1 \\" + eol + "4 \\" + eol + "3" + eol + "f 2 3 4 \\";
    const PolygonSoup s = read_soup(text, MeshFormat::Obj);
    const certify::ObjReadResult c = certify::read_obj(text);
    INFO(c.error);
    REQUIRE(c.ok);
    CHECK(static_cast<std::int64_t>(s.positions.size()) == c.mesh.num_vertices);
    CHECK(s.positions.size() == 4);
    std::vector<int> ours(s.corners.begin(), s.corners.end());
    CHECK(ours == c.mesh.corner_vertex);
    CHECK(ours == std::vector<int>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3});
    CHECK(validate(s).genus == 0);
  }
}

TEST_CASE("binary garbage never crashes a reader") {
  std::uint64_t x = 88172645463325252ULL;
  for (int round = 0; round < 200; ++round) {
    std::string bytes(static_cast<std::size_t>(round * 7 % 300), '\0');
    for (char& c : bytes) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      c = static_cast<char>(x);
    }
    for (MeshFormat f : {MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply, MeshFormat::Stl}) {
      try {
        const PolygonSoup s = read_soup(bytes, f);
        (void)inspect(s);
      } catch (const Error&) {
      }
    }
  }
}

// ---------------------------------------------------------------- shared meshes
namespace {
struct Expect {
  const char* file;
  std::int64_t v, f;
  int genus;
};
}  // namespace

TEST_CASE("shared clean meshes read with the README's V, F and genus") {
  IGM_REQUIRE_DATA(dir);
  const Expect clean[] = {
      {"tetrahedron.off", 4, 4, 0},     {"icosahedron.off", 12, 20, 0},     {"cube.off", 8, 12, 0},
      {"sphere.off", 162, 320, 0},      {"armadillo.off", 26002, 52000, 0}, {"bull.off", 6200, 12396, 0},
      {"pipe.off", 160, 320, 1},        {"mpi_triang.off", 90, 180, 1},     {"knot.off", 2080, 4160, 1},
      {"eight.off", 315, 634, 2},       {"joint.off", 221, 446, 2},         {"helmet.off", 496, 1000, 3},
      {"elephant.off", 2775, 5558, 3},  {"anchor.off", 519, 1050, 4},       {"couplingdown.off", 1841, 3714, 9},
      {"cheese.off", 8629, 17786, 133},
  };
  for (const Expect& e : clean) {
    CAPTURE(e.file);
    const PolygonSoup s = read_soup(dir / "meshes" / "clean" / e.file);
    CHECK(static_cast<std::int64_t>(s.positions.size()) == e.v);
    CHECK(static_cast<std::int64_t>(s.num_faces()) == e.f);
    const MeshReport r = inspect(s);
    CHECK(r.problems.empty());
    CHECK(r.warnings.empty());
    CHECK(r.genus == e.genus);
    const ValidMesh m = validate(s);
    CHECK(m.genus == e.genus);
    CHECK(m.mesh.num_vertices() == e.v);
    CHECK(m.mesh.num_faces() == e.f);
    CHECK(m.mesh.num_vertices() - m.mesh.num_edges() + m.mesh.num_faces() == 2 - 2 * e.genus);
  }
}

TEST_CASE("shared polygonal meshes are triangulated") {
  IGM_REQUIRE_DATA(dir);
  const Expect poly[] = {{"3torus.off", 19, 23, 3}, {"double-torus-example.off", 231, 220, 2}, {"hole.off", 20, 28, 1}};
  for (const Expect& e : poly) {
    CAPTURE(e.file);
    const PolygonSoup s = read_soup(dir / "meshes" / "polygonal" / e.file);
    CHECK(static_cast<std::int64_t>(s.positions.size()) == e.v);
    CHECK(static_cast<std::int64_t>(s.num_faces()) == e.f);
    std::int64_t tris = 0;
    for (std::size_t f = 0; f < s.num_faces(); ++f) tris += static_cast<std::int64_t>(s.face_size(f)) - 2;
    const ValidMesh m = load_mesh(dir / "meshes" / "polygonal" / e.file);
    CHECK(m.genus == e.genus);
    CHECK(m.mesh.num_faces() == tris);
    CHECK(m.mesh.num_faces() > e.f);
    REQUIRE(m.warnings.size() == 1);
    CHECK(m.warnings[0].find("triangulated") != std::string::npos);
  }
}

TEST_CASE("shared repairable meshes are repaired with a warning") {
  IGM_REQUIRE_DATA(dir);
  const MeshReport cube = inspect(read_soup(dir / "meshes" / "repairable" / "cube-shuffled.off"));
  CHECK(cube.problems.empty());
  CHECK(cube.inconsistently_oriented_edges == 9);
  CHECK(cube.genus == 0);
  const ValidMesh mc = load_mesh(dir / "meshes" / "repairable" / "cube-shuffled.off");
  REQUIRE(mc.warnings.size() == 1);
  CHECK(mc.warnings[0].find("re-oriented") != std::string::npos);
  CHECK(mc.warnings[0].find("9 edges") != std::string::npos);
  CHECK(mc.mesh.check_invariants() == "");

  const MeshReport prim = inspect(read_soup(dir / "meshes" / "repairable" / "prim.off"));
  CHECK(prim.problems.empty());
  CHECK(prim.unreferenced_vertices == 3);
  CHECK(prim.polygons == 5);
  const ValidMesh mp = load_mesh(dir / "meshes" / "repairable" / "prim.off");
  CHECK(mp.mesh.num_vertices() == 8);
  CHECK(mp.mesh.num_faces() == 12);
  CHECK(mp.genus == 0);
  REQUIRE(mp.warnings.size() == 2);
  CHECK(mp.warnings[1].find("dropped 3 unreferenced vertices (8, 9, 10)") != std::string::npos);
  CHECK(mp.input_vertex == std::vector<std::int64_t>{0, 1, 2, 3, 4, 5, 6, 7});
}

namespace {
const MeshProblem* find_problem(const MeshReport& r, ErrorKind k) {
  for (const MeshProblem& p : r.problems)
    if (p.kind == k) return &p;
  return nullptr;
}
std::vector<ErrorKind> kinds(const MeshReport& r) {
  std::vector<ErrorKind> k;
  for (const MeshProblem& p : r.problems) k.push_back(p.kind);
  return k;
}
}  // namespace

TEST_CASE("shared invalid meshes are rejected naming the problem, with the README's counts") {
  IGM_REQUIRE_DATA(dir);
  const auto inv = dir / "meshes" / "invalid";
  auto first_kind = [&](const char* f) {
    try {
      load_mesh(inv / f);
    } catch (const Error& e) {
      return e.kind();
    }
    return ErrorKind::Internal;
  };
  {
    const MeshReport r = inspect(read_soup(inv / "b9.ply"));
    CHECK(r.vertices == 22300);
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::NoFaces});
    CHECK(first_kind("b9.ply") == ErrorKind::NoFaces);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "blobby_3cc.off"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::Boundary, ErrorKind::SeveralComponents});
    CHECK(r.components == 3);
    CHECK(r.boundary_loops == 4);
    CHECK(find_problem(r, ErrorKind::Boundary)->count == 4);
    CHECK(find_problem(r, ErrorKind::SeveralComponents)->count == 3);
    CHECK(first_kind("blobby_3cc.off") == ErrorKind::Boundary);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "degtri_sliding.off"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::Boundary});
    CHECK(r.boundary_loops == 1);
    CHECK(first_kind("degtri_sliding.off") == ErrorKind::Boundary);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "double-torus-3-holes.off"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::Boundary});
    CHECK(r.boundary_loops == 3);
    CHECK(r.polygons > 0);
    CHECK(first_kind("double-torus-3-holes.off") == ErrorKind::Boundary);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "knot2.off"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::SeveralComponents});
    CHECK(r.components == 2);
    CHECK(first_kind("knot2.off") == ErrorKind::SeveralComponents);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "pig.stl"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::NonManifoldVertex, ErrorKind::Boundary});
    CHECK(r.non_manifold_vertices == 421);
    CHECK(find_problem(r, ErrorKind::NonManifoldVertex)->count == 421);
    CHECK(r.boundary_loops == 5);
    CHECK(r.components == 1);
    CHECK(first_kind("pig.stl") == ErrorKind::NonManifoldVertex);
  }
  {
    const MeshReport r = inspect(read_soup(inv / "polygon_mesh.off"));
    CHECK(kinds(r) == std::vector<ErrorKind>{ErrorKind::NonManifoldVertex, ErrorKind::Boundary});
    CHECK(r.boundary_loops == 14);
    CHECK(r.non_manifold_vertices == 2);
    CHECK(find_problem(r, ErrorKind::NonManifoldVertex)->elements == std::vector<std::int64_t>{4113, 4349});
    CHECK(first_kind("polygon_mesh.off") == ErrorKind::NonManifoldVertex);
  }
}

TEST_CASE("errors from files name the path") {
  IGM_REQUIRE_DATA(dir);
  const auto pig = dir / "meshes" / "invalid" / "pig.stl";
  try {
    load_mesh(pig);
    FAIL("pig.stl accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::NonManifoldVertex);
    CHECK(std::string(e.what()).rfind("non_manifold_vertex: " + pig.string() + ": 421 vertices", 0) == 0);
    CHECK(e.elements().size() == 100);  // the first 100 of 421
  }
  const auto tmp = std::filesystem::temp_directory_path() / "igm-read-test-bad.obj";
  {
    std::FILE* f = std::fopen(tmp.string().c_str(), "wb");
    REQUIRE(f);
    std::fputs("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n", f);
    std::fclose(f);
  }
  try {
    read_soup(tmp);
    FAIL("bad OBJ accepted");
  } catch (const Error& e) {
    CHECK(e.kind() == ErrorKind::Parse);
    CHECK(std::string(e.what()) == "parse: " + tmp.string() + ": line 4: face corner is not an integer vertex index");
    CHECK(e.elements() == std::vector<std::int64_t>{4});
  }
  std::filesystem::remove(tmp);
}

TEST_CASE("truncated and bit-flipped shared files give typed errors or reports, never crashes") {
  IGM_REQUIRE_DATA(dir);
  std::uint64_t x = 0x9E3779B97F4A7C15ULL;
  for (const char* rel :
       {"clean/cube.off", "polygonal/hole.off", "invalid/pig.stl", "invalid/b9.ply", "repairable/prim.off"}) {
    const auto path = dir / "meshes" / rel;
    const std::string bytes = read_file_bytes(path);
    const MeshFormat fmt = format_from_path(path);
    for (int i = 0; i < 40; ++i) {
      x ^= x << 13, x ^= x >> 7, x ^= x << 17;
      std::string b = bytes.substr(0, static_cast<std::size_t>(x % (bytes.size() + 1)));
      if (i % 2 && !b.empty()) b[x % b.size()] ^= static_cast<char>(1 << (x % 8));
      try {
        const PolygonSoup s = read_soup(b, fmt);
        const MeshReport r = inspect(s);
        try {
          validate(s);
          CHECK(r.problems.empty());
        } catch (const Error& e) {
          REQUIRE_FALSE(r.problems.empty());
          CHECK(e.kind() == r.problems.front().kind);
        }
      } catch (const Error&) {
      }
    }
  }
}
