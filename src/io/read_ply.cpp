// PLY reader: ascii, binary_little_endian and binary_big_endian 1.0. Scalar types char/int8,
// uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32, float/float32,
// double/float64 (and int64/uint64); list properties with any integer count type. The
// `vertex` element gives x, y, z (any numeric type); the `face` element's list
// `vertex_indices` (or `vertex_index`, any integer type) gives the polygons. Other
// properties and elements are skipped. Header lines: `comment` and `obj_info` are skipped;
// a line of any other unknown first word (writers add some: Blender 2.47 wrote a bare
// `Created by ...` line) is skipped with a warning naming its line, since it declares nothing;
// a structural keyword (format, element, property, end_header) in other than lower case is
// rejected, since skipping it would change the layout. Declared counts are checked against
// the bytes that remain before anything is reserved. Cost O(bytes).
#include <bit>
#include <cstring>
#include <string>
#include <vector>

#include "read_detail.h"

namespace igm::detail {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, I64, U64, F32, F64 };

bool type_from_name(std::string_view s, Type& t) {
  struct Entry {
    const char* name;
    Type type;
  };
  static const Entry table[] = {
      {"char", Type::I8},    {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
      {"short", Type::I16},  {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
      {"int", Type::I32},    {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
      {"int64", Type::I64},  {"uint64", Type::U64},  {"float", Type::F32},  {"float32", Type::F32},
      {"double", Type::F64}, {"float64", Type::F64},
  };
  for (const Entry& e : table)
    if (s == e.name) {
      t = e.type;
      return true;
    }
  return false;
}

std::size_t type_size(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8:
      return 1;
    case Type::I16:
    case Type::U16:
      return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32:
      return 4;
    case Type::I64:
    case Type::U64:
    case Type::F64:
      return 8;
  }
  return 1;
}

bool is_integer(Type t) { return t != Type::F32 && t != Type::F64; }

struct Property {
  std::string name;
  bool is_list = false;
  Type count_type = Type::U8;  // lists only
  Type type = Type::F32;       // scalar type or list item type
};

struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

// Reads one binary scalar at p (the caller checked the bytes exist).
template <class T>
T load(const unsigned char* p, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap)
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// A binary value as double (for coordinates) and, for integer types, exactly as int64
// (uint64 above 2^63-1 saturates; it is out of any index range anyway).
struct Value {
  double d = 0;
  std::int64_t i = 0;
};

Value load_value(const unsigned char* p, Type t, bool swap) {
  Value v;
  switch (t) {
    case Type::I8:
      v.i = load<std::int8_t>(p, swap);
      break;
    case Type::U8:
      v.i = load<std::uint8_t>(p, swap);
      break;
    case Type::I16:
      v.i = load<std::int16_t>(p, swap);
      break;
    case Type::U16:
      v.i = load<std::uint16_t>(p, swap);
      break;
    case Type::I32:
      v.i = load<std::int32_t>(p, swap);
      break;
    case Type::U32:
      v.i = load<std::uint32_t>(p, swap);
      break;
    case Type::I64:
      v.i = load<std::int64_t>(p, swap);
      break;
    case Type::U64: {
      std::uint64_t u = load<std::uint64_t>(p, swap);
      v.i = u > static_cast<std::uint64_t>(INT64_MAX) ? INT64_MAX : static_cast<std::int64_t>(u);
      v.d = static_cast<double>(u);
      return v;
    }
    case Type::F32:
      v.d = load<float>(p, swap);
      return v;
    case Type::F64:
      v.d = load<double>(p, swap);
      return v;
  }
  v.d = static_cast<double>(v.i);
  return v;
}

// format, element, property or end_header in any case.
bool structural_keyword(std::string_view key) {
  std::string lower(key);
  for (char& ch : lower)
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  return lower == "format" || lower == "element" || lower == "property" || lower == "end_header";
}

// A keyword for a message: at most 32 bytes, non-printable bytes as '?'.
std::string printable(std::string_view s) {
  std::string out(s.substr(0, 32));
  for (char& ch : out)
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) >= 0x7f) ch = '?';
  return s.size() > 32 ? out + "..." : out;
}

// Role of each property of the vertex and face elements.
enum class Role { Skip, X, Y, Z, Indices };

}  // namespace

PolygonSoup read_ply(std::string_view bytes) {
  TextCursor c(bytes);
  // --- header: line by line until end_header ---
  if (c.take_token() != "ply") c.fail(ErrorKind::Parse, "not a PLY file (no 'ply' magic)");
  c.skip_inline_space();
  if (!c.at_eol()) c.fail(ErrorKind::Parse, "unexpected text after 'ply'");
  c.next_line();
  Format format = Format::Ascii;
  bool have_format = false, have_end = false;
  std::vector<Element> elements;
  PolygonSoup soup;
  constexpr std::int64_t kMaxSkipWarnings = 10;  // then one line counts the rest
  std::int64_t line = 1, skipped = 0;
  while (!c.at_end()) {  // one header line per round (no call below crosses a newline)
    ++line;
    c.skip_inline_space();
    const std::string_view key = c.take_token();
    const bool known = key == "format" || key == "element" || key == "property" || key == "end_header";
    c.skip_inline_space();
    if (key == "format") {
      const std::string_view f = c.take_token();
      if (f == "ascii")
        format = Format::Ascii;
      else if (f == "binary_little_endian")
        format = Format::BinaryLE;
      else if (f == "binary_big_endian")
        format = Format::BinaryBE;
      else
        c.fail(ErrorKind::Parse, "unknown PLY format '" + std::string(f) + "'");
      c.skip_inline_space();
      if (c.take_token() != "1.0") c.fail(ErrorKind::Unsupported, "PLY version other than 1.0");
      have_format = true;
    } else if (key == "element") {
      Element e;
      e.name = std::string(c.take_token());
      c.skip_inline_space();
      const std::string_view n = c.take_token();
      const char* q = parse_int(n.data(), n.data() + n.size(), e.count);
      if (e.name.empty() || !q || q != n.data() + n.size() || e.count < 0)
        c.fail(ErrorKind::Parse, "bad element declaration (expected: element NAME COUNT)");
      elements.push_back(std::move(e));
    } else if (key == "property") {
      if (elements.empty()) c.fail(ErrorKind::Parse, "property before any element");
      Property prop;
      std::string_view t = c.take_token();
      if (t == "list") {
        prop.is_list = true;
        c.skip_inline_space();
        const std::string_view ct = c.take_token();
        if (!type_from_name(ct, prop.count_type) || !is_integer(prop.count_type))
          c.fail(ErrorKind::Parse, "bad list count type '" + std::string(ct) + "'");
        c.skip_inline_space();
        t = c.take_token();
      }
      if (!type_from_name(t, prop.type)) c.fail(ErrorKind::Parse, "unknown property type '" + std::string(t) + "'");
      c.skip_inline_space();
      prop.name = std::string(c.take_token());
      if (prop.name.empty()) c.fail(ErrorKind::Parse, "property without a name");
      elements.back().props.push_back(std::move(prop));
    } else if (key == "end_header") {
      c.next_line();
      have_end = true;
      break;
    } else if (key == "comment" || key == "obj_info" || key.empty()) {
      // ignored
    } else if (structural_keyword(key)) {
      c.fail(ErrorKind::Parse, "PLY header keyword '" + std::string(key) + "' must be lower case");
    } else {
      if (++skipped <= kMaxSkipWarnings)
        soup.warnings.push_back("PLY header line " + std::to_string(line) + " skipped (unknown keyword '" +
                                printable(key) + "')");
    }
    c.skip_inline_space();
    if (known && !c.at_eol())
      c.fail(ErrorKind::Parse, "unexpected text at the end of a header line");
    c.next_line();
  }
  if (!have_end) c.fail(ErrorKind::Parse, "PLY header without end_header (truncated?)");
  if (skipped > kMaxSkipWarnings)
    soup.warnings.push_back(std::to_string(skipped - kMaxSkipWarnings) + " more unknown PLY header lines skipped");
  if (!have_format) throw Error(ErrorKind::Parse, "PLY header without a format line");

  // --- roles ---
  std::vector<std::vector<Role>> roles(elements.size());
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = elements[e];
    roles[e].assign(el.props.size(), Role::Skip);
    int found = 0;
    for (std::size_t k = 0; k < el.props.size(); ++k) {
      const Property& pr = el.props[k];
      if (el.name == "vertex" && !pr.is_list && (pr.name == "x" || pr.name == "y" || pr.name == "z")) {
        roles[e][k] = pr.name == "x" ? Role::X : pr.name == "y" ? Role::Y : Role::Z;
        ++found;
      }
      if (el.name == "face" && pr.is_list && (pr.name == "vertex_indices" || pr.name == "vertex_index")) {
        if (!is_integer(pr.type)) throw Error(ErrorKind::Parse, "PLY face indices must have an integer type");
        roles[e][k] = Role::Indices;
      }
    }
    if (el.name == "vertex" && found != 3 && el.count > 0)
      throw Error(ErrorKind::Parse, "PLY vertex element needs scalar properties x, y and z");
  }

  std::vector<std::int64_t> face;
  const std::size_t body = static_cast<std::size_t>(c.p - bytes.data());

  if (format == Format::Ascii) {
    auto next_token = [&](const char* what) {
      while (c.p < c.end && is_space_or_newline(*c.p)) ++c.p;
      if (c.at_end()) c.fail(ErrorKind::Parse, std::string("unexpected end of file: expected ") + what);
      return c.take_token();
    };
    for (std::size_t e = 0; e < elements.size(); ++e) {
      const Element& el = elements[e];
      if (el.props.empty()) continue;  // nothing to read, whatever the count
      // Each property takes at least one character and one separator.
      const auto remaining = static_cast<std::int64_t>(c.end - c.p);
      const auto per = static_cast<std::int64_t>(2 * el.props.size());
      if (el.count > (remaining + 1) / per)
        throw Error(ErrorKind::TooLarge,
                    "PLY element '" + el.name + "' declares " + std::to_string(el.count) + " items but only " +
                        std::to_string(remaining) + " bytes follow (truncated?)",
                    {el.count});
      const bool is_vertex = el.name == "vertex", is_face = el.name == "face";
      if (is_vertex) soup.positions.reserve(soup.positions.size() + static_cast<std::size_t>(el.count));
      if (is_face) soup.face_begin.reserve(soup.face_begin.size() + static_cast<std::size_t>(el.count));
      for (std::int64_t i = 0; i < el.count; ++i) {  // bounded by count, bounded by the bytes
        Vec3d pos;
        for (std::size_t k = 0; k < el.props.size(); ++k) {
          const Property& pr = el.props[k];
          const Role role = roles[e][k];
          if (pr.is_list) {
            const std::string_view t = next_token("a list count");
            std::int64_t n = 0;
            const char* q = parse_int(t.data(), t.data() + t.size(), n);
            if (!q || q != t.data() + t.size() || n < 0)
              throw_at_line(ErrorKind::Parse, bytes, t.data(), "bad list count '" + std::string(t) + "'");
            if (n > (c.end - c.p) / 2 + 1)
              throw_at_line(ErrorKind::TooLarge, bytes, t.data(),
                            "list of " + std::to_string(n) + " items is longer than the file");
            if (role == Role::Indices) face.clear();
            for (std::int64_t j = 0; j < n; ++j) {  // bounded by n, bounded by the bytes
              const std::string_view v = next_token("a list item");
              if (role == Role::Indices) {
                std::int64_t idx = 0;
                const char* r = parse_int(v.data(), v.data() + v.size(), idx);
                if (!r || r != v.data() + v.size())
                  throw_at_line(ErrorKind::Parse, bytes, v.data(), "bad vertex index '" + std::string(v) + "'");
                face.push_back(idx);
              }
            }
            if (role == Role::Indices) {
              if (face.size() < 3)
                throw_at_line(ErrorKind::Parse, bytes, t.data(),
                              "face " + std::to_string(i) + " has " + std::to_string(face.size()) +
                                  " corners (at least 3 needed)");
              soup.add_face(face.begin(), face.end());
            }
          } else {
            const std::string_view t = next_token("a property value");
            double d = 0;
            const char* q = parse_double(t.data(), t.data() + t.size(), d);
            if (!q || q != t.data() + t.size())
              throw_at_line(ErrorKind::Parse, bytes, t.data(), "bad number '" + std::string(t) + "'");
            if (role == Role::X)
              pos.x = d;
            else if (role == Role::Y)
              pos.y = d;
            else if (role == Role::Z)
              pos.z = d;
          }
        }
        if (is_vertex) soup.positions.push_back(pos);
      }
    }
    return soup;
  }

  // --- binary ---
  const bool swap = (format == Format::BinaryLE) != (std::endian::native == std::endian::little);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const std::size_t size = bytes.size();
  std::size_t pos = body;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = elements[e];
    std::size_t min_size = 0;  // bytes of one item with every list empty
    for (const Property& pr : el.props) min_size += pr.is_list ? type_size(pr.count_type) : type_size(pr.type);
    if (min_size == 0) continue;
    if (static_cast<std::uint64_t>(el.count) > (size - pos) / min_size)
      throw_at_byte(ErrorKind::TooLarge, pos,
                    "PLY element '" + el.name + "' declares " + std::to_string(el.count) + " items of at least " +
                        std::to_string(min_size) + " bytes but only " + std::to_string(size - pos) +
                        " bytes follow (truncated?)");
    const bool is_vertex = el.name == "vertex", is_face = el.name == "face";
    if (is_vertex) soup.positions.reserve(soup.positions.size() + static_cast<std::size_t>(el.count));
    if (is_face) soup.face_begin.reserve(soup.face_begin.size() + static_cast<std::size_t>(el.count));
    for (std::int64_t i = 0; i < el.count; ++i) {  // bounded by count, bounded by the bytes
      Vec3d p3;
      for (std::size_t k = 0; k < el.props.size(); ++k) {
        const Property& pr = el.props[k];
        const Role role = roles[e][k];
        if (pr.is_list) {
          const std::size_t cs = type_size(pr.count_type);
          if (size - pos < cs)
            throw_at_byte(ErrorKind::Parse, pos, "unexpected end of file in a list count (truncated?)");
          const std::int64_t n = load_value(data + pos, pr.count_type, swap).i;
          if (n < 0) throw_at_byte(ErrorKind::Parse, pos, "negative list count");
          pos += cs;
          const std::size_t is = type_size(pr.type);
          if (static_cast<std::uint64_t>(n) > (size - pos) / is)
            throw_at_byte(ErrorKind::TooLarge, pos,
                          "list of " + std::to_string(n) + " items is longer than the file (truncated?)");
          if (role == Role::Indices) {
            if (n < 3)
              throw_at_byte(ErrorKind::Parse, pos - cs,
                            "face " + std::to_string(i) + " has " + std::to_string(n) + " corners (at least 3 needed)");
            face.clear();
            for (std::int64_t j = 0; j < n; ++j) face.push_back(load_value(data + pos + j * is, pr.type, swap).i);
            soup.add_face(face.begin(), face.end());
          }
          pos += static_cast<std::size_t>(n) * is;
        } else {
          const std::size_t s = type_size(pr.type);
          if (size - pos < s) throw_at_byte(ErrorKind::Parse, pos, "unexpected end of file (truncated?)");
          if (role != Role::Skip) {
            const double d = load_value(data + pos, pr.type, swap).d;
            if (role == Role::X)
              p3.x = d;
            else if (role == Role::Y)
              p3.y = d;
            else
              p3.z = d;
          }
          pos += s;
        }
      }
      if (is_vertex) soup.positions.push_back(p3);
    }
  }
  return soup;
}

}  // namespace igm::detail
