#include "igm/io/read_mesh.h"

#include <cctype>
#include <cstdio>
#include <memory>
#include <string>

#include "read_detail.h"

namespace igm {

MeshFormat format_from_path(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".stl") return MeshFormat::Stl;
  throw Error(ErrorKind::Io, "unknown mesh file extension '" + path.extension().string() + "' of " + path.string() +
                                 " (expected .obj, .off, .ply or .stl)");
}

PolygonSoup read_soup(std::string_view bytes, MeshFormat format) {
  switch (format) {
    case MeshFormat::Obj:
      return detail::read_obj(bytes);
    case MeshFormat::Off:
      return detail::read_off(bytes);
    case MeshFormat::Ply:
      return detail::read_ply(bytes);
    case MeshFormat::Stl:
      return detail::read_stl(bytes);
  }
  throw Error(ErrorKind::InvalidArgument, "unknown mesh format");
}

std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error(ErrorKind::Io, "no such file: " + path.string());
  if (std::filesystem::is_directory(path, ec)) throw Error(ErrorKind::Io, "is a directory: " + path.string());
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.string().c_str(), "rb"), &std::fclose);
  if (!f) throw Error(ErrorKind::Io, "cannot open " + path.string());
  std::string bytes;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  char buf[1 << 16];
  for (;;) {  // bounded by the file size
    const std::size_t n = std::fread(buf, 1, sizeof buf, f.get());
    bytes.append(buf, n);
    if (n < sizeof buf) break;
  }
  if (std::ferror(f.get())) throw Error(ErrorKind::Io, "read error on " + path.string());
  return bytes;
}

PolygonSoup read_soup(const std::filesystem::path& path) {
  const MeshFormat format = format_from_path(path);
  const std::string bytes = read_file_bytes(path);
  try {
    return read_soup(std::string_view(bytes), format);
  } catch (const Error& e) {
    throw with_path(e, path);
  }
}

Error with_path(const Error& e, const std::filesystem::path& path) {
  return Error(e.kind(), path.string() + ": " + e.message(), e.elements());
}

}  // namespace igm
