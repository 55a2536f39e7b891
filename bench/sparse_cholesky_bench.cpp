// Sparse Cholesky benchmark (embed/sparse_cholesky.h): the systems of the embeddings and of
// smoothing's Newton steps, on the vertex graphs of the shared meshes and of generated ones:
//   tutte   the graph Laplacian plus a small diagonal shift (one unknown per vertex);
//   newton  2 x 2 blocks per vertex pair (two unknowns per vertex, grouped), diagonally dominant.
// Side by side on the same matrix: SparseCholesky (CHOLMOD's analysis, its own supernodal
// factorization or CHOLMOD's simplicial one; `--threads N`), and CHOLMOD alone: supernodal (with
// this machine's BLAS: ldd says which) and simplicial, each with METIS and with AMD. Times are
// wall seconds (the machine is shared: run twice, or compare within one run); each variant also
// solves and reports the relative residual.
// usage: igm_bench_sparse_cholesky [--threads N] [--only own|cholmod] [--max-faces F] [MESH ...]
#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "igm/core/threads.h"
#include "igm/embed/sparse_cholesky.h"
#include "igm/mesh/generate.h"
#include "igm/mesh/validate.h"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct System {
  std::vector<int> xadj{0}, adj, group;
  std::vector<double> val, diag;
};

// The symmetric system of a mesh's vertex graph with `block` unknowns per vertex.
System make_system(const igm::ValidMesh& mesh, int block) {
  const int nv = mesh.mesh.num_vertices();
  std::vector<std::vector<int>> nb(nv);
  for (int f = 0; f < mesh.mesh.num_faces(); ++f) {
    const auto t = mesh.mesh.face_vertices(f);
    for (int i = 0; i < 3; ++i) nb[t[i]].push_back(t[(i + 1) % 3]), nb[t[(i + 1) % 3]].push_back(t[i]);
  }
  System s;
  for (int v = 0; v < nv; ++v) {
    std::sort(nb[v].begin(), nb[v].end());
    nb[v].erase(std::unique(nb[v].begin(), nb[v].end()), nb[v].end());
    for (int r = 0; r < block; ++r) {
      double sum = 1e-3;
      std::vector<std::pair<int, double>> row;
      if (block == 2) row.push_back({v * 2 + (1 - r), 0.05});
      for (int w : nb[v])
        for (int c = 0; c < block; ++c) row.push_back({w * block + c, c == r ? -1.0 : 0.1});
      std::sort(row.begin(), row.end());
      for (auto [j, x] : row) s.adj.push_back(j), s.val.push_back(x), sum += std::abs(x);
      s.xadj.push_back(static_cast<int>(s.adj.size()));
      s.diag.push_back(sum);
      s.group.push_back(v);
    }
  }
  if (block == 1) s.group.clear();
  return s;
}

double residual(const System& s, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  Eigen::VectorXd r = b;
  for (std::size_t i = 0; i < s.diag.size(); ++i) {
    r[i] -= s.diag[i] * x[i];
    for (int k = s.xadj[i]; k < s.xadj[i + 1]; ++k) r[i] -= s.val[k] * x[s.adj[k]];
  }
  return r.norm() / b.norm();
}

int g_threads = 0;

void run_own(const System& s) {
  igm::with_threads(g_threads, [&] {
    igm::SparseCholesky chol;
    auto t0 = Clock::now();
    chol.analyze(s.xadj, s.adj, s.group);
    const double ta = since(t0);
    t0 = Clock::now();
    if (!chol.factorize_numeric(s.val, s.diag)) std::printf("  NOT POSITIVE DEFINITE\n");
    const double tf1 = since(t0);
    t0 = Clock::now();
    chol.factorize_numeric(s.val, s.diag);
    const double tf2 = since(t0);
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(s.diag.size()));
    Eigen::MatrixXd x = b;
    t0 = Clock::now();
    chol.solve(x);
    const double ts = since(t0);
    const igm::SparseCholeskyStats& st = chol.stats();
    std::printf("  %-22s analyze %7.2f  factorize %7.2f %7.2f  solve %6.2f  | %s %s, %zu entries, %.3g flops, %d supernodes, "
                "max front %d, threads %d, residual %.1e\n",
                "SparseCholesky", ta, tf1, tf2, ts, st.metis ? "METIS" : "AMD", st.supernodal ? "supernodal" : "simplicial",
                st.factor_entries, st.flops, st.supernodes, st.max_front, igm::resolve_threads(g_threads),
                residual(s, x.col(0), b));
  });
}

void run_cholmod(const System& s, bool supernodal, bool metis) {
  cholmod_common cm;
  cholmod_l_start(&cm);
  cm.print = 0;
  cm.nmethods = 1;
  cm.method[0].ordering = metis ? CHOLMOD_METIS : CHOLMOD_AMD;
  cm.postorder = 1;
  cm.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
  const long n = static_cast<long>(s.diag.size());
  long nnz = n;
  for (long i = 0; i < n; ++i)
    for (int k = s.xadj[i]; k < s.xadj[i + 1]; ++k) nnz += s.adj[k] < i;
  cholmod_sparse* A = cholmod_l_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &cm);  // upper, by columns
  auto* p = static_cast<SuiteSparse_long*>(A->p);
  auto* ii = static_cast<SuiteSparse_long*>(A->i);
  auto* x = static_cast<double*>(A->x);
  long q = 0;
  for (long j = 0; j < n; ++j) {  // column j of the upper triangle = row j's entries left of j
    p[j] = q;
    for (int k = s.xadj[j]; k < s.xadj[j + 1]; ++k)
      if (s.adj[k] < j) ii[q] = s.adj[k], x[q++] = s.val[k];
    ii[q] = j, x[q++] = s.diag[j];
  }
  p[n] = q;
  auto t0 = Clock::now();
  cholmod_factor* L = cholmod_l_analyze(A, &cm);
  const double ta = since(t0);
  t0 = Clock::now();
  cholmod_l_factorize(A, L, &cm);
  const double tf1 = since(t0);
  t0 = Clock::now();
  cholmod_l_factorize(A, L, &cm);
  const double tf2 = since(t0);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
  cholmod_dense B{};
  B.nrow = B.d = B.nzmax = static_cast<std::size_t>(n);
  B.ncol = 1;
  B.x = b.data();
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  t0 = Clock::now();
  cholmod_dense* X = cholmod_l_solve(CHOLMOD_A, L, &B, &cm);
  const double ts = since(t0);
  const Eigen::VectorXd xs = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(X->x), n);
  char name[64];
  std::snprintf(name, sizeof name, "CHOLMOD %s %s", supernodal ? "supernodal" : "simplicial", metis ? "METIS" : "AMD");
  std::printf("  %-22s analyze %7.2f  factorize %7.2f %7.2f  solve %6.2f  | lnz %.3g, %.3g flops, status %d, residual %.1e\n",
              name, ta, tf1, tf2, ts, cm.lnz, cm.fl, cm.status, residual(s, xs, b));
  cholmod_l_free_dense(&X, &cm);
  cholmod_l_free_factor(&L, &cm);
  cholmod_l_free_sparse(&A, &cm);
  cholmod_l_finish(&cm);
}

std::string g_only;

void run(const std::string& name, const igm::ValidMesh& mesh) {
  for (int block : {1, 2}) {
    const System s = make_system(mesh, block);
    std::printf("%s %s: %zu unknowns, %zu off-diagonal entries\n", name.c_str(), block == 1 ? "tutte" : "newton",
                s.diag.size(), s.adj.size());
    if (g_only != "cholmod") run_own(s);
    if (g_only != "own")
      for (bool super : {true, false})
        for (bool metis : {true, false}) run_cholmod(s, super, metis);
    std::fflush(stdout);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes;
  std::int64_t max_faces = 1000000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--threads" && i + 1 < argc) g_threads = std::atoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc) g_only = argv[++i];
    else if (a == "--max-faces" && i + 1 < argc) max_faces = std::atoll(argv[++i]);
    else meshes.push_back(a);
  }
  try {
    if (!meshes.empty()) {
      for (const std::string& m : meshes) run(std::filesystem::path(m).stem().string(), igm::load_mesh(m));
      return 0;
    }
    const char* env = std::getenv("IGM_DATA_DIR");
    const std::filesystem::path data = env && *env ? env : "../shared";
    for (const char* m : {"eight", "elephant", "couplingdown", "cheese", "armadillo"}) {
      const auto path = data / "meshes" / "clean" / (std::string(m) + ".off");
      if (std::filesystem::exists(path)) run(m, igm::load_mesh(path));
    }
    for (const std::int64_t faces : {std::int64_t{100000}, std::int64_t{1000000}}) {
      if (faces > max_faces) continue;
      igm::GenerateOptions g;
      g.genus = 20;
      g.faces = faces;
      run("generated-g20-" + std::to_string(faces), igm::validate(igm::generate_closed_mesh(g)));
    }
  } catch (const igm::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
