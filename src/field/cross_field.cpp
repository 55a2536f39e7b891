#include "igm/field/cross_field.h"

#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <utility>

#include "igm/core/error.h"
#include "igm/core/det_math.h"
#include "field_internal.h"
#include "igm/field/curvature.h"

namespace igm {

const char* to_string(FieldSolver solver) {
  switch (solver) {
    case FieldSolver::InverseIteration: return "inverse_iteration";
    case FieldSolver::ShiftInvertLanczos: return "shift_invert_lanczos";
  }
  return "unknown";
}

namespace {

using namespace field_internal;

// The field's system on the free faces (slot: face -> free index, or -1) plus shift M: CHOLMOD's
// simplicial factorization of restricted(), or above real_form_above faces the real form on
// every face (LargeFactor, its analysis kept in `large`). solve() takes and returns vectors over
// the free faces.
class ComplexFactor {
 public:
  ComplexFactor(const System& s, const std::vector<int>& free_faces, const std::vector<int>& slot, double shift,
                int real_form_above, LargeFactor& large, double& seconds)
      : free_(free_faces), n_(static_cast<int>(s.mass.size())) {
    if (n_ > real_form_above) {
      large_ = &large;
      large.factorize(s, slot, shift, seconds);
    } else {
      small_.compute(restricted(s, free_faces, slot, shift), seconds);
    }
  }
  ~ComplexFactor() {
    if (large_) large_->release();
  }
  ComplexFactor(const ComplexFactor&) = delete;
  ComplexFactor& operator=(const ComplexFactor&) = delete;
  Vec solve(const Vec& b) const {
    if (!large_) return small_.solve(b);
    Vec full = Vec::Zero(n_);
    for (std::size_t i = 0; i < free_.size(); ++i) full[free_[i]] = b[static_cast<Eigen::Index>(i)];
    const Vec x = large_->solve(full);
    Vec r(static_cast<Eigen::Index>(free_.size()));
    for (std::size_t i = 0; i < free_.size(); ++i) r[static_cast<Eigen::Index>(i)] = x[free_[i]];
    return r;
  }

 private:
  const std::vector<int>& free_;
  int n_;
  Factor<Complex> small_;
  LargeFactor* large_ = nullptr;
};

constexpr double kPi = std::numbers::pi;
constexpr double kQuarter = kPi / 2;

std::string vname(int v) { return "vertex " + std::to_string(v); }

// ---------------------------------------------------------------------------------------------
// Input checks: sizes, finite positions, twins, one fan per vertex, one component.
void check_input(const TriMesh& mesh, const std::vector<Vec3d>& positions, const CrossFieldOptions& o) {
  if (!(o.alignment >= 0) || !std::isfinite(o.alignment))
    throw Error(ErrorKind::InvalidArgument, "cross field: alignment must be finite and >= 0");
  if (o.max_iterations < 1 || !(o.tolerance >= 0) || !(o.close_pair_distance >= 0) || o.cleanup_rounds < 0 ||
      !(o.split_distance >= 0 && o.split_distance <= 8) || o.real_form_above < 0)
    throw Error(ErrorKind::InvalidArgument,
                "cross field: max_iterations >= 1, tolerance >= 0, close_pair_distance >= 0, cleanup_rounds >= 0, "
                "split_distance in [0, 8], real_form_above >= 0");
  const int nv = mesh.num_vertices(), nf = mesh.num_faces(), nh = mesh.num_halfedges();
  if (!o.constrained_edges.empty()) {
    if (static_cast<int>(o.constrained_edges.size()) != nh)
      throw Error(ErrorKind::InvalidArgument, "cross field: " + std::to_string(o.constrained_edges.size()) +
                                                  " constrained-edge flags for " + std::to_string(nh) + " half-edges");
    for (int h = 0; h < nh; ++h) {
      const int t = mesh.twin(h);
      if (o.constrained_edges[h] && t >= 0 && t < nh && !o.constrained_edges[t])
        throw Error(ErrorKind::InvalidArgument,
                    "cross field: half-edge " + std::to_string(h) + " is constrained but its twin is not", {h});
    }
  }
  if (static_cast<int>(positions.size()) != nv)
    throw Error(ErrorKind::InvalidArgument, "cross field: " + std::to_string(positions.size()) +
                                                " positions for " + std::to_string(nv) + " vertices");
  if (nv == 0) throw Error(ErrorKind::Empty, "cross field: the mesh has no vertices");
  if (nf == 0) throw Error(ErrorKind::NoFaces, "cross field: the mesh has no faces");
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h), v = mesh.origin(h);
    if (v < 0 || v >= nv)
      throw Error(ErrorKind::Internal, "cross field: half-edge " + std::to_string(h) + " has no valid origin", {h});
    if (t >= nh || t < -1 || (t >= 0 && (mesh.twin(t) != h || mesh.origin(t) != mesh.target(h))))
      throw Error(ErrorKind::Internal, "cross field: half-edge " + std::to_string(h) + " has an inconsistent twin",
                  {h});
  }
  for (int v = 0; v < nv; ++v) {
    const Vec3d& p = positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(ErrorKind::NonFinite, "cross field: " + vname(v) + " has a non-finite coordinate", {v});
  }
  std::vector<int> out(nv, 0);
  for (int h = 0; h < nh; ++h) ++out[mesh.origin(h)];
  for (int v = 0; v < nv; ++v) {
    const int first = mesh.vertex_halfedge(v);
    if (first < 0)
      throw Error(ErrorKind::SeveralComponents, "cross field: " + vname(v) + " is used by no face", {v});
    int count = 0;
    for (int h = first; h >= 0 && count <= out[v];) {
      ++count;
      h = mesh.next_around_origin(h);
      if (h == first) break;
    }
    if (count != out[v])
      throw Error(ErrorKind::NonManifoldVertex,
                  "cross field: the faces around " + vname(v) + " form more than one fan", {v});
  }
  std::vector<char> reached(nf, 0);
  std::vector<int> stack{0};
  reached[0] = 1;
  int count = 1;
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int i = 0; i < 3; ++i) {
      const int t = mesh.twin(3 * f + i);
      if (t >= 0 && !reached[TriMesh::face(t)]) {
        reached[TriMesh::face(t)] = 1;
        ++count;
        stack.push_back(TriMesh::face(t));
      }
    }
  }
  if (count != nf) {
    int f = 0;
    while (reached[f]) ++f;
    throw Error(ErrorKind::SeveralComponents,
                "cross field: face " + std::to_string(f) + " is not connected to face 0 (one surface at a time)", {f});
  }
}

// Positions times a power of two putting the largest coordinate magnitude in [0.5, 1): exact,
// so directions and angles are unchanged, and no product of coordinates overflows or underflows.
std::vector<Vec3d> scaled_positions(const std::vector<Vec3d>& positions) {
  double m = 0;
  for (const Vec3d& p : positions) m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  if (!(m > 0)) return positions;
  int e = 0;
  std::frexp(m, &e);
  std::vector<Vec3d> out(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i)
    out[i] = {std::ldexp(positions[i].x, -e), std::ldexp(positions[i].y, -e), std::ldexp(positions[i].z, -e)};
  return out;
}

double m_norm(const Vec& x, const std::vector<double>& mass) {
  double s = 0;
  for (Eigen::Index i = 0; i < x.size(); ++i) s += mass[i] * std::norm(x[i]);
  return std::sqrt(s);
}

double rayleigh(const SpMat& A, const Vec& x, const std::vector<double>& mass) {
  const Vec ax = A * x;
  const double num = x.dot(ax).real();  // x* A x (Eigen's dot conjugates the first argument)
  const double den = m_norm(x, mass);
  return den > 0 ? num / (den * den) : 0.0;
}

// The energy u* A u / u* M u of the unit field u_f = exp(4 i theta_f).
double unit_energy(const System& sys, const std::vector<double>& theta) {
  Vec u(static_cast<Eigen::Index>(theta.size()));
  for (std::size_t f = 0; f < theta.size(); ++f) {
    const SinCos r = det_sincos(4 * theta[f]);
    u[static_cast<Eigen::Index>(f)] = Complex(r.cos, r.sin);
  }
  return rayleigh(sys.A, u, sys.mass);
}

// The smoothest field of a closed surface: the eigenvector of A u = lambda M u of the smallest
// eigenvalue. A may be singular (a parallel field exists, e.g. on a cube), so A + eps M with eps
// 1e-10 of the mean diagonal of M^-1 A is factorized; this moves no eigenvector.
Vec smallest_eigenvector(const System& s, const CrossFieldOptions& o, LargeFactor& large, CrossFieldStats& st) {
  const int n = static_cast<int>(s.mass.size());
  std::vector<int> all(n), slot(n);
  for (int i = 0; i < n; ++i) all[i] = slot[i] = i;
  double scale = 0;
  for (int f = 0; f < n; ++f) scale += s.A.coeff(f, f).real() / s.mass[f];
  const double eps = 1e-10 * scale / n;
  const ComplexFactor factor(s, all, slot, eps, o.real_form_above, large, st.factor_seconds);
  Vec mvec(n);
  for (int f = 0; f < n; ++f) mvec[f] = s.mass[f];
  if (o.solver == FieldSolver::InverseIteration) {
    Vec x = Vec::Ones(n);  // the fixed start: u = 1 in every face's frame
    x /= m_norm(x, s.mass);
    double energy = rayleigh(s.A, x, s.mass);
    st.converged = false;
    for (int k = 0; k < o.max_iterations; ++k) {
      x = factor.solve(mvec.cwiseProduct(x));
      const double nx = m_norm(x, s.mass);
      if (!(nx > 0) || !std::isfinite(nx))
        throw Error(ErrorKind::Internal, "cross field: inverse iteration broke down (non-finite iterate)");
      x /= nx;
      const double e = rayleigh(s.A, x, s.mass);
      st.iterations = k + 1;
      const bool done = std::fabs(energy - e) <= o.tolerance * (e + eps);
      energy = e;
      if (done) {
        st.converged = true;
        break;
      }
    }
    return x;
  }
  // Shift-invert Lanczos on the real symmetric form of M^-1/2 (A + eps M) M^-1/2 (size 2n: the
  // real and imaginary parts), whose largest eigenvalues of the inverse are wanted.
  struct Op {
    using Scalar = double;
    const ComplexFactor* factor;
    const std::vector<double>* mass;
    int n;
    int* applications;
    Eigen::Index rows() const { return 2 * n; }
    Eigen::Index cols() const { return 2 * n; }
    void set_shift(double) {}
    void perform_op(const double* in, double* out) const {
      Vec b(n);
      for (int i = 0; i < n; ++i) b[i] = Complex(in[i], in[n + i]) / std::sqrt((*mass)[i]);
      // (M^-1/2 (A + eps M) M^-1/2)^-1 = M^1/2 (A + eps M)^-1 M^1/2
      for (int i = 0; i < n; ++i) b[i] *= (*mass)[i];
      const Vec x = factor->solve(b);
      for (int i = 0; i < n; ++i) {
        const Complex v = x[i] * std::sqrt((*mass)[i]);
        out[i] = v.real();
        out[n + i] = v.imag();
      }
      ++*applications;
    }
  };
  int applications = 0;
  Op op{&factor, &s.mass, n, &applications};
  const int ncv = std::min(2 * n, 20);
  const int nev = std::min(2, 2 * n - 1);
  Spectra::SymEigsShiftSolver<Op> eig(op, std::max(nev, 1), std::max(ncv, nev + 1), 0.0);
  eig.init();  // Spectra's fixed default start vector: deterministic
  eig.compute(Spectra::SortRule::LargestMagn, o.max_iterations, std::max(o.tolerance, 1e-14));
  st.iterations = applications;
  st.converged = eig.info() == Spectra::CompInfo::Successful;
  Vec x(n);
  if (eig.info() == Spectra::CompInfo::NotComputed || eig.eigenvectors().cols() == 0)
    throw Error(ErrorKind::Internal, "cross field: Lanczos found no eigenvector");
  const Eigen::MatrixXd v = eig.eigenvectors();
  const Eigen::VectorXd lambda = eig.eigenvalues();
  Eigen::Index best = 0;  // the smallest eigenvalue (its two real copies are equivalent)
  for (Eigen::Index j = 1; j < lambda.size(); ++j)
    if (lambda[j] < lambda[best]) best = j;
  for (int i = 0; i < n; ++i) x[i] = Complex(v(i, best), v(n + i, best)) / std::sqrt(s.mass[i]);
  return x;
}

// The field minimizing E(u) + c |u - q|^2_M with u fixed on the faces where fixed_value is set:
// (A_II + c M_II) u_I = c M_II q_I - A_IB u_B.
Vec linear_field(const System& s, const std::vector<Complex>& q, double c, const std::vector<char>& fixed,
                 const Vec& fixed_value, int real_form_above, LargeFactor& large, CrossFieldStats& st) {
  const int n = static_cast<int>(s.mass.size());
  std::vector<int> free_faces, slot(n, -1);
  for (int f = 0; f < n; ++f)
    if (!fixed[f]) {
      slot[f] = static_cast<int>(free_faces.size());
      free_faces.push_back(f);
    }
  Vec u = fixed_value;
  if (free_faces.empty()) return u;
  Vec b(static_cast<Eigen::Index>(free_faces.size()));
  for (std::size_t i = 0; i < free_faces.size(); ++i) {
    const int f = free_faces[i];
    Complex r = c > 0 ? c * s.mass[f] * q[f] : Complex(0, 0);
    for (SpMat::InnerIterator it(s.A, f); it; ++it)  // column f = conj of row f (Hermitian)
      if (fixed[it.row()]) r -= std::conj(it.value()) * fixed_value[it.row()];
    b[static_cast<Eigen::Index>(i)] = r;
  }
  const ComplexFactor factor(s, free_faces, slot, c, real_form_above, large, st.factor_seconds);
  const Vec x = factor.solve(b);
  if (!x.allFinite()) throw Error(ErrorKind::Internal, "cross field: the linear solve gave a non-finite field");
  for (std::size_t i = 0; i < free_faces.size(); ++i) u[free_faces[i]] = x[static_cast<Eigen::Index>(i)];
  return u;
}

// theta in [0, pi/2) from u = |u| exp(4 i theta) (0 for u = 0).
double angle_of(const Complex& u) {
  double t = det_atan2(u.imag(), u.real()) / 4;  // in [-pi/4, pi/4]
  if (t < 0) t += kQuarter;
  if (!(t < kQuarter)) t = 0;  // t == pi/2 after rounding: the same cross
  return t;
}

}  // namespace

// -----------------------------------------------------------------------------------------------

void derive_singularities(const TriMesh& mesh, CrossField& field) {
  const int nv = mesh.num_vertices(), nh = mesh.num_halfedges();
  const FaceFrames& fr = field.frames;
  field.period.assign(nh, 0);
  field.matching.assign(nh, 0);
  for (int h = 0; h < nh; ++h) {
    const int t = mesh.twin(h);
    if (t < 0 || t < h) continue;
    const double d = field.theta[TriMesh::face(t)] - field.theta[TriMesh::face(h)] - fr.transport[h];
    const int p = static_cast<int>(std::lround(d / kQuarter));
    field.period[h] = p;
    field.period[t] = -p;
    field.matching[h] = static_cast<std::uint8_t>(((-p) % 4 + 4) % 4);
    field.matching[t] = static_cast<std::uint8_t>((p % 4 + 4) % 4);
  }
  auto q_of = [&](int b) {  // the field direction nearest to boundary half-edge b in its face
    const double d = fr.edge_angle[b] - field.theta[TriMesh::face(b)];
    return static_cast<int>(std::lround(d / kQuarter));
  };
  field.valence.assign(nv, 4);
  field.on_boundary.assign(nv, 0);
  field.cones.clear();
  field.corners.clear();
  field.stats.valence_count.fill(0);
  field.stats.boundary_count.fill(0);
  for (int v = 0; v < nv; ++v) {
    const int first = mesh.vertex_halfedge(v);
    if (first < 0) continue;
    long long turns = 0, periods = 0;
    int n = 0, refs = 0;
    int o = first, b_in = -1;
    for (int step = 0; step < nh; ++step) {
      const int f = TriMesh::face(o);
      ++n;
      if (mesh.origin(fr.reference[f]) == v) ++refs;
      const int h = TriMesh::prev(o);
      const int t = mesh.twin(h);
      if (t < 0) {
        b_in = h;
        break;
      }
      turns += fr.transport_turns[h];
      periods += field.period[h];
      o = t;
      if (o == first) break;
    }
    const bool boundary = b_in >= 0;
    long long val = 4 * (static_cast<long long>(n) - 1 - refs + turns) + periods;
    val += boundary ? q_of(b_in) + 2 - q_of(first) : 4;
    field.valence[v] = static_cast<int>(val);
    field.on_boundary[v] = boundary ? 1 : 0;
    const int capped = static_cast<int>(std::clamp<long long>(val, 0, 8));
    if (boundary) {
      ++field.stats.boundary_count[capped];
      if (val != 2) field.corners.push_back({v, static_cast<int>(val)});
    } else {
      ++field.stats.valence_count[capped];
      if (val != 4) field.cones.push_back({v, static_cast<int>(val)});
    }
  }
}

std::string check_poincare_hopf(const TriMesh& mesh, const CrossField& field) {
  const int nv = mesh.num_vertices(), nh = mesh.num_halfedges();
  if (static_cast<int>(field.valence.size()) != nv || static_cast<int>(field.on_boundary.size()) != nv)
    return "the field has " + std::to_string(field.valence.size()) + " valences for " + std::to_string(nv) +
           " vertices";
  long long edges = 0;
  for (int h = 0; h < nh; ++h)
    if (mesh.twin(h) < h) ++edges;
  const long long chi = static_cast<long long>(nv) - edges + mesh.num_faces();
  long long interior = 0, boundary = 0;
  for (int v = 0; v < nv; ++v) {
    if (field.on_boundary[v])
      boundary += 2 - field.valence[v];
    else
      interior += 4 - field.valence[v];
  }
  if (interior + boundary == 4 * chi) return "";
  return "Poincare-Hopf violated: sum (4 - valence) over interior vertices = " + std::to_string(interior) +
         ", sum (2 - k) over boundary vertices = " + std::to_string(boundary) + ", 4 chi = " + std::to_string(4 * chi);
}

std::string seamless_obstruction(const TriMesh& mesh, const CrossField& field) {
  const int nv = mesh.num_vertices(), nh = mesh.num_halfedges();
  if (static_cast<int>(field.valence.size()) != nv || static_cast<int>(field.on_boundary.size()) != nv)
    return "the field has " + std::to_string(field.valence.size()) + " valences for " + std::to_string(nv) + " vertices";
  bool boundary = false;
  for (int v = 0; v < nv; ++v) {
    boundary = boundary || field.on_boundary[v];
    if (field.valence[v] < 1)
      return std::string(field.on_boundary[v] ? "boundary " : "") + vname(v) + " has " +
             (field.on_boundary[v] ? "k = " : "valence ") + std::to_string(field.valence[v]) +
             " (a cone angle k pi/2 needs k >= 1)";
  }
  long long edges = 0;
  for (int h = 0; h < nh; ++h)
    if (mesh.twin(h) < h) ++edges;
  const long long chi = static_cast<long long>(nv) - edges + mesh.num_faces();
  if (!boundary && chi == 0 && field.cones.size() == 2) {
    const Cone& a = field.cones[0];
    const Cone& b = field.cones[1];
    if (std::min(a.valence, b.valence) == 3 && std::max(a.valence, b.valence) == 5)
      return "a torus whose only cones are one of valence 3 (" + vname(a.valence == 3 ? a.vertex : b.vertex) +
             ") and one of valence 5 has no seamless map";
  }
  return "";
}

int field_rotation(const TriMesh& mesh, const CrossField& field, const std::vector<int>& crossed) {
  const int nh = mesh.num_halfedges();
  int sum = 0;
  for (std::size_t i = 0; i < crossed.size(); ++i) {
    const int h = crossed[i];
    if (h < 0 || h >= nh || mesh.twin(h) < 0)
      throw Error(ErrorKind::InvalidArgument,
                  "field_rotation: half-edge " + std::to_string(h) + " is not an interior half-edge", {h});
    const int next = crossed[(i + 1) % crossed.size()];
    if (next < 0 || next >= nh || TriMesh::face(next) != TriMesh::face(mesh.twin(h)))
      throw Error(ErrorKind::InvalidArgument,
                  "field_rotation: the path does not continue from half-edge " + std::to_string(h), {h});
    sum += field.matching[h];
  }
  return sum % 4;
}

Vec3d field_direction(const CrossField& field, int f, int k) {
  return frame_direction(field.frames, f, field.theta[f] + k * kQuarter);
}

struct CrossFieldCache::Impl {
  field_internal::LargeFactor large;
};
CrossFieldCache::CrossFieldCache() : impl_(std::make_unique<Impl>()) {}
CrossFieldCache::~CrossFieldCache() = default;
int CrossFieldCache::analyses() const { return impl_->large.analyses(); }

CrossField compute_cross_field(const TriMesh& mesh, const std::vector<Vec3d>& input_positions,
                               const CrossFieldOptions& options, CrossFieldCache* cache) {
  std::optional<CrossFieldCache> local;  // only when the caller keeps none
  field_internal::LargeFactor& large = (cache ? cache : &local.emplace())->impl_->large;
  const auto t0 = Clock::now();
  check_input(mesh, input_positions, options);
  const std::vector<Vec3d> p = scaled_positions(input_positions);
  const int nf = mesh.num_faces();
  CrossField field;
  CrossFieldStats& st = field.stats;
  st.solver = options.solver;
  field.frames = face_frames(mesh, p, options.constrained_edges);
  const FaceFrames& fr = field.frames;
  st.degenerate_faces = fr.degenerate_faces;
  const System sys = build_system(mesh, p, fr);
  // Boundary and feature constraints: the reference half-edge is the constrained edge, u = exp(0) = 1.
  std::vector<char> fixed(nf, 0);
  Vec fixed_value = Vec::Zero(nf);
  for (int f = 0; f < nf; ++f)
    if (mesh.twin(fr.reference[f]) < 0 ||
        (!options.constrained_edges.empty() && options.constrained_edges[fr.reference[f]])) {
      fixed[f] = 1;
      fixed_value[f] = 1;
      ++st.constrained_faces;
    }
  std::vector<Complex> q;
  double c = 0;
  if (options.alignment > 0) {
    // The guide scaled to unit mean square (M-weighted), so that it weighs the same as the unit
    // boundary values whatever the surface's size (the curvature is in 1 / length).
    q = curvature_cross_guide(mesh, p, fr);
    double square = 0;
    for (int f = 0; f < nf; ++f) square += sys.mass[f] * std::norm(q[f]);
    const double rms = std::sqrt(square / sys.total_area);
    if (rms > 0 && std::isfinite(rms) && sys.total_area > 0) {
      for (Complex& z : q) z /= rms;
      c = options.alignment / sys.total_area;
    }
  }
  Vec u;
  if (st.constrained_faces > 0 || c > 0) {
    st.linear = true;
    st.iterations = 1;
    u = linear_field(sys, q, c, fixed, fixed_value, options.real_form_above, large, st);
  } else {
    u = smallest_eigenvector(sys, options, large, st);
  }
  field.theta.resize(nf);
  for (int f = 0; f < nf; ++f) field.theta[f] = fixed[f] ? 0.0 : angle_of(u[f]);
  // The positions were scaled by a power of two: the mean edge length in the caller's units.
  st.mean_edge_length = mean_edge_length(mesh, input_positions);
  derive_singularities(mesh, field);
  field.close_pairs = close_cone_pairs(mesh, p, field, options.close_pair_distance);
  st.cones_before_cleanup = static_cast<int>(field.cones.size());
  st.pairs_before_cleanup = static_cast<int>(field.close_pairs.size());
  if (options.remove_close_pairs || options.split_valence1 || options.split_valence2 || options.split_valence6)
    clean_cones(mesh, p, sys, fixed, options, field);
  st.energy = unit_energy(sys, field.theta) * sys.total_area;
  st.seconds = since(t0);
  return field;
}

}  // namespace igm
