#include "igm/output/schema_svg.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>

namespace igm {

void write_schema_svg(std::ostream& out, const SchemaDrawing& d, std::size_t max_mesh_edges) {
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  for (const Vec2d& p : d.polygon) {
    lo_x = std::min(lo_x, p.x), lo_y = std::min(lo_y, p.y);
    hi_x = std::max(hi_x, p.x), hi_y = std::max(hi_y, p.y);
  }
  for (const auto& path : d.side_paths)
    for (const Vec2d& p : path) {
      lo_x = std::min(lo_x, p.x), lo_y = std::min(lo_y, p.y);
      hi_x = std::max(hi_x, p.x), hi_y = std::max(hi_y, p.y);
    }
  if (d.polygon.empty()) lo_x = lo_y = 0, hi_x = hi_y = 1;
  const double size = 800, margin = 40;
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1e-300});
  const double scale = (size - 2 * margin) / span;
  char buf[256];
  auto X = [&](const Vec2d& p) { return margin + (p.x - lo_x) * scale; };
  auto Y = [&](const Vec2d& p) { return size - margin - (p.y - lo_y) * scale; };
  auto line = [&](const Vec2d& a, const Vec2d& b, const char* style) {
    std::snprintf(buf, sizeof buf, "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" %s/>\n", X(a), Y(a), X(b), Y(b),
                  style);
    out << buf;
  };
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"800\" height=\"800\" viewBox=\"0 0 800 800\">\n"
      << "<rect width=\"800\" height=\"800\" fill=\"white\"/>\n<g>\n";
  const std::size_t stride = d.mesh_edges.size() > max_mesh_edges ? d.mesh_edges.size() / max_mesh_edges + 1 : 1;
  for (std::size_t i = 0; i < d.mesh_edges.size(); i += stride)
    line(d.mesh_edges[i][0], d.mesh_edges[i][1], "stroke=\"#b0b0b0\" stroke-width=\"0.3\"");
  out << "</g>\n<g>\n";
  for (const auto& e : d.diagonals) line(e[0], e[1], "stroke=\"#555555\" stroke-width=\"1\" stroke-dasharray=\"6,4\"");
  for (const auto& e : d.template_edges) line(e[0], e[1], "stroke=\"black\" stroke-width=\"2.5\"");
  out << "</g>\n<g>\n";
  const std::size_t n = d.polygon.size();
  for (std::size_t s = 0; s < n; ++s) {
    const std::size_t pair = s < d.side_pair.size() ? static_cast<std::size_t>(d.side_pair[s]) : s;
    const std::size_t key = std::min(s, pair);
    const double hue = n ? 360.0 * static_cast<double>(key) / static_cast<double>(n) * 1.618 : 0;
    char style[64];
    std::snprintf(style, sizeof style, "stroke=\"hsl(%.0f,75%%,45%%)\" stroke-width=\"5\"",
                  hue - 360.0 * static_cast<long>(hue / 360.0));
    if (s < d.side_pair.size() && d.side_pair[s] < 0)  // a free side: the surface's boundary
      std::snprintf(style, sizeof style, "stroke=\"#707070\" stroke-width=\"5\" stroke-dasharray=\"2,3\"");
    if (s < d.side_paths.size() && d.side_paths[s].size() >= 2) {
      for (std::size_t i = 0; i + 1 < d.side_paths[s].size(); ++i) line(d.side_paths[s][i], d.side_paths[s][i + 1], style);
    } else {
      line(d.polygon[s], d.polygon[(s + 1) % n], style);
    }
  }
  out << "</g>\n<g>\n";
  for (const Vec2d& c : d.cones) {
    std::snprintf(buf, sizeof buf, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"4\" fill=\"#d02020\"/>\n", X(c), Y(c));
    out << buf;
  }
  out << "</g>\n</svg>\n";
}

}  // namespace igm
