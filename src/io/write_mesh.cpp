#include "igm/io/write_mesh.h"

#include <charconv>
#include <cstdio>
#include <memory>

#include "igm/core/error.h"

namespace igm {

namespace {

void append_double(std::string& s, double d) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, d);  // shortest round-trip form
  if (ec != std::errc()) throw Error(ErrorKind::Internal, "cannot format a double");
  s.append(buf, end);
}

void append_int(std::string& s, long long v) {
  char buf[24];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;  // 24 bytes always hold a 64-bit integer
  s.append(buf, end);
}

void check_triangles(std::size_t nv, const std::vector<std::array<int, 3>>& triangles) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles[t])
      if (v < 0 || static_cast<std::size_t>(v) >= nv)
        throw Error(ErrorKind::IndexOutOfRange,
                    "triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) + " of " + std::to_string(nv),
                    {static_cast<std::int64_t>(t)});
}

void append_xyz(std::string& s, const Vec3d& p) {
  append_double(s, p.x);
  s += ' ';
  append_double(s, p.y);
  s += ' ';
  append_double(s, p.z);
  s += '\n';
}

}  // namespace

std::string format_obj(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles) {
  check_triangles(positions.size(), triangles);
  std::string s;
  s.reserve(40 * positions.size() + 24 * triangles.size());
  for (const Vec3d& p : positions) {
    s += "v ";
    append_xyz(s, p);
  }
  for (const auto& t : triangles) {
    s += 'f';
    for (int v : t) {
      s += ' ';
      append_int(s, static_cast<long long>(v) + 1);
    }
    s += '\n';
  }
  return s;
}

std::string format_off(const std::vector<Vec3d>& positions, const std::vector<std::array<int, 3>>& triangles) {
  check_triangles(positions.size(), triangles);
  std::string s = "OFF\n";
  s.reserve(40 * positions.size() + 24 * triangles.size());
  append_int(s, static_cast<long long>(positions.size()));
  s += ' ';
  append_int(s, static_cast<long long>(triangles.size()));
  s += " 0\n";
  for (const Vec3d& p : positions) append_xyz(s, p);
  for (const auto& t : triangles) {
    s += '3';
    for (int v : t) {
      s += ' ';
      append_int(s, v);
    }
    s += '\n';
  }
  return s;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.string().c_str(), "wb"), &std::fclose);
  if (!f) throw Error(ErrorKind::Io, "cannot open " + path.string() + " for writing");
  if (std::fwrite(text.data(), 1, text.size(), f.get()) != text.size())
    throw Error(ErrorKind::Io, "write error on " + path.string());
  std::FILE* raw = f.release();
  if (std::fclose(raw) != 0) throw Error(ErrorKind::Io, "write error on " + path.string());
}

void write_obj(const std::filesystem::path& path, const std::vector<Vec3d>& positions,
               const std::vector<std::array<int, 3>>& triangles) {
  write_text_file(path, format_obj(positions, triangles));
}

void write_off(const std::filesystem::path& path, const std::vector<Vec3d>& positions,
               const std::vector<std::array<int, 3>>& triangles) {
  write_text_file(path, format_off(positions, triangles));
}

}  // namespace igm
