#include "igm/output/quad_svg.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

namespace igm {

namespace {

Vec3d operator-(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d operator+(const Vec3d& a, const Vec3d& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3d operator*(double s, const Vec3d& a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool finite(const Vec3d& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
// a / |a|, or (0, 0, 0) when |a| is 0 or not finite.
Vec3d unit(const Vec3d& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 && std::isfinite(n) ? (1.0 / n) * a : Vec3d{0, 0, 0};
}

// The viewing frame: right, up, towards the viewer (right x up = view).
struct Frame {
  Vec3d right, up, view;
};

// Principal axes of the positions, e[0] of largest spread, each with its largest component > 0.
std::array<Vec3d, 3> principal_axes(const std::vector<Vec3d>& ps) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const Vec3d& p : ps)
    if (finite(p)) mean += Eigen::Vector3d(p.x, p.y, p.z), ++n;
  if (n > 0) mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3d& p : ps)
    if (finite(p)) {
      const Eigen::Vector3d d = Eigen::Vector3d(p.x, p.y, p.z) - mean;
      cov += d * d.transpose();
    }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // eigenvalues ascending
  std::array<Vec3d, 3> axes;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d v = eig.info() == Eigen::Success ? Eigen::Vector3d(eig.eigenvectors().col(2 - k))
                                                     : Eigen::Vector3d::Unit(2 - k);
    Eigen::Index big = 0;
    v.cwiseAbs().maxCoeff(&big);
    if (v[big] < 0) v = -v;
    axes[k] = {v.x(), v.y(), v.z()};
  }
  return axes;
}

Frame view_frame(const std::vector<Vec3d>& ps, const Vec3d& requested) {
  const std::array<Vec3d, 3> e = principal_axes(ps);
  Frame f;
  f.view = unit(requested);
  if (dot(f.view, f.view) == 0) f.view = unit(e[2] + 0.5 * e[1] + 0.35 * e[0]);
  for (const Vec3d& a : {e[0], e[1], e[2]}) {  // the first axis not along the view
    f.right = unit(a - dot(a, f.view) * f.view);
    if (dot(f.right, f.right) > 0.5) break;
  }
  f.up = cross(f.view, f.right);
  return f;
}

const char* valence_colour(int valence) {
  switch (valence) {
    case 3: return "#1f5fd6";
    case 5: return "#d62728";
    case 6: return "#ff7f0e";
    default: return valence < 3 ? "#9467bd" : "#222222";
  }
}

struct Quad {
  std::size_t id;
  double depth;
  double shade;  // Lambert intensity in [0.3, 1]
  bool front;    // faces the viewer (for the orientation of positive volume)
};

}  // namespace

QuadSvgStats write_quad_svg(std::ostream& out, const QuadMesh& mesh, const QuadSvgOptions& options) {
  QuadSvgStats stats;
  stats.quads = mesh.quads.size();
  const int size = std::clamp(options.size, 64, 16384);
  const auto nv = static_cast<int>(mesh.positions.size());
  const Frame f = view_frame(mesh.positions, options.view);
  const Vec3d light = unit(-0.35 * f.right + 0.5 * f.up + 0.8 * f.view);

  // Valences, the quads that can be drawn, their depth, shade and facing.
  std::vector<int> valence(mesh.positions.size(), 0);
  std::vector<Quad> quads;
  double volume = 0;
  for (std::size_t q = 0; q < mesh.quads.size(); ++q) {
    const auto& c = mesh.quads[q];
    bool ok = true;
    for (int v : c) ok = ok && v >= 0 && v < nv && finite(mesh.positions[static_cast<std::size_t>(v)]);
    if (!ok) continue;
    for (int v : c) ++valence[static_cast<std::size_t>(v)];
    const Vec3d p[4] = {mesh.positions[c[0]], mesh.positions[c[1]], mesh.positions[c[2]], mesh.positions[c[3]]};
    volume += dot(p[0], cross(p[1], p[2])) + dot(p[0], cross(p[2], p[3]));
    Vec3d n = unit(cross(p[2] - p[0], p[3] - p[1]));
    const bool front = dot(n, f.view) > 0;
    if (!front) n = -1.0 * n;
    const double depth = 0.25 * (dot(p[0], f.view) + dot(p[1], f.view) + dot(p[2], f.view) + dot(p[3], f.view));
    quads.push_back({q, depth, 0.3 + 0.7 * std::max(0.0, dot(n, light)), front});
  }
  // The subset (QuadSvgOptions::max_quads): back faces first, then every k-th in depth order.
  const std::size_t drawable = quads.size();
  if (quads.size() > options.max_quads) {
    const bool outward = volume >= 0;
    quads.erase(std::remove_if(quads.begin(), quads.end(), [&](const Quad& q) { return q.front != outward; }),
                quads.end());
  }
  std::sort(quads.begin(), quads.end(), [](const Quad& a, const Quad& b) {
    return a.depth != b.depth ? a.depth < b.depth : a.id < b.id;
  });
  if (quads.size() > options.max_quads && options.max_quads > 0) {
    const std::size_t k = (quads.size() + options.max_quads - 1) / options.max_quads;
    std::vector<Quad> kept;
    for (std::size_t i = 0; i < quads.size(); i += k) kept.push_back(quads[i]);
    quads.swap(kept);
  } else if (options.max_quads == 0) {
    quads.clear();
  }
  stats.quads_drawn = quads.size();

  // The picture's frame: the projected bounding box of the drawn quads' corners.
  double lo_x = std::numeric_limits<double>::max(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  double edge_sum = 0;
  for (const Quad& q : quads)
    for (int k = 0; k < 4; ++k) {
      const Vec3d& p = mesh.positions[mesh.quads[q.id][k]];
      const double x = dot(p, f.right), y = dot(p, f.up);
      lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x), lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
      const Vec3d d = mesh.positions[mesh.quads[q.id][(k + 1) % 4]] - p;
      edge_sum += std::hypot(dot(d, f.right), dot(d, f.up));
    }
  if (quads.empty()) lo_x = lo_y = 0, hi_x = hi_y = 1;
  const double margin = 0.05 * size;
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1e-300});
  const double scale = (size - 2 * margin) / span;
  const double off_x = margin + 0.5 * ((size - 2 * margin) - (hi_x - lo_x) * scale);
  const double off_y = margin + 0.5 * ((size - 2 * margin) - (hi_y - lo_y) * scale);
  const auto X = [&](const Vec3d& p) { return off_x + (dot(p, f.right) - lo_x) * scale; };
  const auto Y = [&](const Vec3d& p) { return size - off_y - (dot(p, f.up) - lo_y) * scale; };
  const double edge_px = quads.empty() ? 10 : edge_sum * scale / (4.0 * static_cast<double>(quads.size()));
  const double stroke = std::clamp(0.08 * edge_px, 0.1, 1.2);
  const double radius = std::clamp(0.3 * edge_px, 1.5, 6.0);

  // Each irregular vertex is marked after the last (nearest) drawn quad around it.
  std::vector<std::size_t> last_quad(mesh.positions.size(), SIZE_MAX);
  for (std::size_t i = 0; i < quads.size(); ++i)
    for (int v : mesh.quads[quads[i].id]) last_quad[static_cast<std::size_t>(v)] = i;
  std::vector<std::vector<int>> marks_after(quads.size());
  for (int v = 0; v < nv; ++v) {
    const int val = valence[static_cast<std::size_t>(v)];
    if (val == 0 || val == 4) continue;
    ++stats.irregular[val];
    const std::size_t last = last_quad[static_cast<std::size_t>(v)];
    if (last != SIZE_MAX) marks_after[last].push_back(v);
  }

  char buf[320];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\">\n"
                "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n"
                "<g stroke=\"#1a2a3a\" stroke-width=\"%.2f\" stroke-linejoin=\"round\">\n",
                size, size, size, size, size, size, stroke);
  out << buf;
  for (std::size_t i = 0; i < quads.size(); ++i) {
    const auto& c = mesh.quads[quads[i].id];
    const double s = quads[i].shade;
    std::snprintf(buf, sizeof buf,
                  "<polygon points=\"%.1f,%.1f %.1f,%.1f %.1f,%.1f %.1f,%.1f\" fill=\"rgb(%d,%d,%d)\"/>\n",
                  X(mesh.positions[c[0]]), Y(mesh.positions[c[0]]), X(mesh.positions[c[1]]), Y(mesh.positions[c[1]]),
                  X(mesh.positions[c[2]]), Y(mesh.positions[c[2]]), X(mesh.positions[c[3]]), Y(mesh.positions[c[3]]),
                  static_cast<int>(158 * s), static_cast<int>(197 * s), static_cast<int>(232 * s));
    out << buf;
    for (int v : marks_after[i]) {
      const int val = valence[static_cast<std::size_t>(v)];
      std::snprintf(buf, sizeof buf,
                    "<circle class=\"valence-%d\" cx=\"%.1f\" cy=\"%.1f\" r=\"%.1f\" fill=\"%s\" stroke=\"white\"/>\n",
                    val, X(mesh.positions[v]), Y(mesh.positions[v]), radius, valence_colour(val));
      out << buf;
    }
  }
  out << "</g>\n";

  // The legend: the quad count, the subset if any, one entry per valence present.
  const int rows = 1 + (stats.quads_drawn < drawable ? 1 : 0) +
                   std::max<int>(1, static_cast<int>(stats.irregular.size()));
  std::snprintf(buf, sizeof buf,
                "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"13\">\n"
                "<rect x=\"8\" y=\"8\" width=\"230\" height=\"%d\" fill=\"white\" fill-opacity=\"0.85\" "
                "stroke=\"#888888\"/>\n",
                12 + 18 * rows);
  out << buf;
  int y = 26;
  std::snprintf(buf, sizeof buf, "<text x=\"16\" y=\"%d\">%zu quads</text>\n", y, stats.quads);
  out << buf;
  if (stats.quads_drawn < drawable) {
    y += 18;
    std::snprintf(buf, sizeof buf, "<text x=\"16\" y=\"%d\">%zu drawn (subset)</text>\n", y, stats.quads_drawn);
    out << buf;
  }
  if (stats.irregular.empty()) {
    y += 18;
    std::snprintf(buf, sizeof buf, "<text x=\"16\" y=\"%d\">every vertex of valence 4</text>\n", y);
    out << buf;
  }
  for (const auto& [val, count] : stats.irregular) {
    y += 18;
    std::snprintf(buf, sizeof buf,
                  "<circle cx=\"22\" cy=\"%d\" r=\"5\" fill=\"%s\" stroke=\"white\"/>"
                  "<text x=\"34\" y=\"%d\">valence %d: %zu %s</text>\n",
                  y - 4, valence_colour(val), y, val, count, count == 1 ? "vertex" : "vertices");
    out << buf;
  }
  out << "</g>\n</svg>\n";
  return stats;
}

}  // namespace igm
