// igm batch: `igm run` over a data set.
//
//   igm batch DIR|LIST|MESH -o OUT [-j N] [--timeout S] [--memory-mb M] [-- RUN OPTIONS]
//   igm batch --summary -o OUT
//
// The job: every .obj .off .ply .stl file under DIR (recursively, in path order, OUT excluded),
// or the paths of LIST (a text file, one path a line, relative to the current folder; blank and
// '#' lines skipped), or the one MESH. Each mesh runs as `igm run MESH -o OUT/runs/ID RUN
// OPTIONS` in a process of its own (fork and exec of /proc/self/exe, in its own process group,
// killed if the batch dies), its stdout and stderr in OUT/runs/ID/igm.log and igm.err, with
// - a wall-time limit (--timeout S, default 3600 s; 0: none): past it the process group is
//   killed (SIGKILL) and the verdict is `timeout`;
// - a memory limit (--memory-mb M, default none): RLIMIT_AS of M MB in the child (address
//   space, more than resident memory: leave room), and `--memory-limit-mb M` passed to the run
//   unless RUN OPTIONS set it, so that genus >= 1 runs stop before their arrangement outgrows it.
// ID is the file's stem and a hash of its absolute path (two meshes of one name do not meet).
// Up to N (-j, default 1) run at once. Each finished mesh appends one line to OUT/results.jsonl
// with a single write() on an O_APPEND descriptor, so several batches (GNU parallel: `parallel
// igm batch {} -o OUT ::: FILES`) can share OUT; a mesh whose line is there already is skipped
// (resuming an interrupted batch runs each mesh once). A line:
//   {"file": ABSOLUTE PATH, "id": ID, "verdict": V, "exit": CODE or null, "signal": SIG or null,
//    ["error_kind": KIND, "error": MESSAGE,] "seconds": WALL, "peak_mb": PEAK RSS,
//    ["quads": Q, "raised_by_floor": B,] ["quality": {"sj_median": X, "sj_below_half": Y}]}
// V: certified (exit 0), rejected (exit 1: the certifier refused an output), invalid_input
// (exit 2; error_kind is the igm::Error kind or "usage"), timeout, out_of_memory (the run's own
// memory stop, a failed allocation, a start refused for memory, a signal before any output
// under --memory-mb, or a SIGKILL not ours: the OOM killer), crashed (any other signal or exit
// code; error_kind "internal" for exit 3). quality copies quality.quads.sj_median and sj_below_half from the run's NAME.cert.json when present.
// quads is its stats.quads; raised_by_floor whether the floor (PipelineOptions) raised a surface
// above the size asked.
// Progress: a bar on stderr when it is a terminal, else one line per mesh. At the end (not in
// the one-MESH form) a summary of the job's lines on stdout: counts by verdict, time and
// quality quantiles; `--summary` prints it for every line of OUT/results.jsonl.
#include "batch_command.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "igm/core/threads.h"
#include "json.h"

namespace igm_cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kExitOk = 0, kExitUsage = 2;
constexpr const char* kVerdicts[] = {"certified", "rejected", "invalid_input", "timeout", "out_of_memory", "crashed"};

int usage(const std::string& message) {
  std::fprintf(stderr,
               "igm batch: %s\n"
               "usage: igm batch DIR|LIST|MESH -o OUT [-j N] [--timeout S] [--memory-mb M] [-- RUN OPTIONS]\n"
               "       igm batch --summary -o OUT\n"
               "  runs `igm run MESH -o OUT/runs/ID RUN OPTIONS` for each mesh in a process of its own and\n"
               "  appends one JSON line per mesh to OUT/results.jsonl (meshes with a line are skipped)\n"
               "  -j N           meshes at once (1..256, default 1); each run gets 1/N of the cores (--threads)\n"
               "  --timeout S    wall-time limit per mesh in seconds (default 3600; 0: none)\n"
               "  --memory-mb M  address-space limit per mesh in MB (default none)\n"
               "  --summary      print the summary of OUT/results.jsonl and exit\n"
               "  several batches may share OUT, e.g. GNU parallel: parallel -j4 igm batch {} -o OUT ::: FILES\n",
               message.c_str());
  return kExitUsage;
}

bool is_mesh_path(const fs::path& p) {
  std::string ext = p.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".obj" || ext == ".off" || ext == ".ply" || ext == ".stl";
}

// The identity of a mesh in results.jsonl: its absolute, lexically normal path.
std::string mesh_key(const fs::path& p) { return fs::absolute(p).lexically_normal().string(); }

// stem-XXXXXXXX: the file's stem and the FNV-1a hash of its key.
std::string run_id(const std::string& key) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : key) h = (h ^ c) * 16777619u;
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", h);
  return fs::path(key).stem().string() + "-" + hex;
}

bool inside(const fs::path& p, const fs::path& dir) {
  const auto rel = p.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != "..";
}

// The meshes of the job (keys, deduplicated, in order). Throws std::runtime_error with a
// message for an unreadable input.
std::vector<std::string> collect(const fs::path& input, const fs::path& out) {
  std::vector<std::string> keys;
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    const fs::path out_abs = fs::absolute(out).lexically_normal();
    // Bound: the files under DIR (directory symlinks are not followed, so no cycles).
    for (auto it = fs::recursive_directory_iterator(input, fs::directory_options::skip_permission_denied, ec);
         !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
      const fs::path abs = fs::absolute(it->path()).lexically_normal();
      if (it->is_directory(ec) && (abs == out_abs || inside(abs, out_abs))) {
        it.disable_recursion_pending();
        continue;
      }
      if (it->is_regular_file(ec) && is_mesh_path(it->path())) keys.push_back(abs.string());
    }
    if (ec) throw std::runtime_error("cannot list " + input.string() + ": " + ec.message());
    std::sort(keys.begin(), keys.end());
  } else if (is_mesh_path(input)) {
    keys.push_back(mesh_key(input));
  } else {
    std::ifstream list(input);
    if (!list) throw std::runtime_error("cannot read " + input.string());
    std::string line;
    while (std::getline(list, line)) {  // bound: the lines of the list
      const auto b = line.find_first_not_of(" \t\r");
      if (b == std::string::npos || line[b] == '#') continue;
      const auto e = line.find_last_not_of(" \t\r");
      keys.push_back(mesh_key(line.substr(b, e + 1 - b)));
    }
  }
  std::vector<std::string> unique;
  std::set<std::string> seen;
  for (const std::string& k : keys)
    if (seen.insert(k).second) unique.push_back(k);
  return unique;
}

// The parsed lines of OUT/results.jsonl (malformed ones, e.g. cut by a crash, are skipped).
std::vector<Json> read_results(const fs::path& file) {
  std::vector<Json> records;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {  // bound: the lines of the file
    std::optional<Json> j = parse_json(line);
    if (j && j->type == Json::Type::Object && !j->string_of("file").empty()) records.push_back(std::move(*j));
  }
  return records;
}

struct Outcome {
  std::string verdict, error_kind, error;
  std::optional<int> exit_code, signal;
  double seconds = 0, peak_mb = 0;
  std::optional<double> sj_median, sj_below_half;
  std::optional<double> quads;  // the run's quad count (stats.quads of NAME.cert.json)
  bool raised_by_floor = false;  // a surface got more quads than asked: the least its layout allows
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool has(const std::string& text, std::string_view needle) { return text.find(needle) != std::string::npos; }

// The kind and message of `igm run`'s error line "igm: MESH: KIND: MESSAGE" in stderr (an older
// `igm run` repeated "MESH: " before the message).
void parse_run_error(const std::string& err, const std::string& mesh, Outcome& o) {
  const std::string prefix = "igm: " + mesh + ": ";
  const auto at = err.rfind(prefix);
  if (at == std::string::npos) {  // a usage error of `igm run`: its first line
    o.error_kind = "usage";
    o.error = err.substr(0, err.find('\n'));
    return;
  }
  std::string rest = err.substr(at + prefix.size());
  rest = rest.substr(0, rest.find('\n'));
  const auto colon = rest.find(": ");
  o.error_kind = colon == std::string::npos ? "unknown" : rest.substr(0, colon);
  o.error = colon == std::string::npos ? rest : rest.substr(colon + 2);
  if (o.error.compare(0, mesh.size() + 2, mesh + ": ") == 0) o.error.erase(0, mesh.size() + 2);
}

struct Child {
  std::string key, id;
  pid_t pid = -1;
  int exec_errno_fd = -1;  // read end of a close-on-exec pipe: the child's exec errno, if any
  Clock::time_point start, deadline;
  bool has_deadline = false, timed_out = false;
};

struct Settings {
  fs::path out;
  int jobs = 1;
  double timeout = 3600;
  long long memory_mb = 0;
  std::vector<std::string> run_options;
};

// Forks and execs `/proc/self/exe run KEY -o OUT/runs/ID OPTIONS`. Throws on fork failure.
Child start(const std::string& key, const Settings& s) {
  Child c;
  c.key = key;
  c.id = run_id(key);
  const fs::path dir = s.out / "runs" / c.id;
  std::error_code ec;
  fs::create_directories(dir, ec);
  std::vector<std::string> argv_s = {"igm", "run", key, "-o", dir.string()};
  argv_s.insert(argv_s.end(), s.run_options.begin(), s.run_options.end());
  const bool own_limit = std::find(s.run_options.begin(), s.run_options.end(), "--memory-limit-mb") !=
                         s.run_options.end();
  if (s.memory_mb > 0 && !own_limit) argv_s.insert(argv_s.end(), {"--memory-limit-mb", std::to_string(s.memory_mb)});
  // The cores divided among the runs: each gets its share (at least 1) unless the run options
  // set --threads (the outputs are the same for any count).
  const bool own_threads = std::find(s.run_options.begin(), s.run_options.end(), "--threads") != s.run_options.end();
  if (!own_threads)
    argv_s.insert(argv_s.end(), {"--threads", std::to_string(std::max(1, igm::resolve_threads(0) / s.jobs))});
  std::vector<char*> argv;
  for (std::string& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = (dir / "igm.log").string(), err = (dir / "igm.err").string();
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  const pid_t parent = getpid();
  c.start = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {  // the child: async-signal-safe calls only until exec
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);  // the batch blocks SIGCHLD; igm run starts clean
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);  // the batch died before prctl
    const int o = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int devnull = open("/dev/null", O_RDONLY);
    for (const auto& [fd, target] : {std::pair{o, STDOUT_FILENO}, std::pair{e, STDERR_FILENO},
                                    std::pair{devnull, STDIN_FILENO}})
      if (fd >= 0) {
        dup2(fd, target);
        close(fd);
      }
    if (s.memory_mb > 0) {
      const rlim_t bytes = static_cast<rlim_t>(s.memory_mb) << 20;
      const rlimit lim{bytes, bytes};
      setrlimit(RLIMIT_AS, &lim);
    }
    execv("/proc/self/exe", argv.data());
    const int error = errno;
    [[maybe_unused]] const ssize_t n = write(fds[1], &error, sizeof error);
    _exit(127);
  }
  close(fds[1]);
  setpgid(pid, pid);  // also here: no race with the kill below
  c.pid = pid;
  c.exec_errno_fd = fds[0];
  if (s.timeout > 0) {
    c.has_deadline = true;
    c.deadline = c.start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s.timeout));
  }
  return c;
}

// The verdict of a finished child.
Outcome classify(const Child& c, int status, const rusage& ru, const Settings& s) {
  Outcome o;
  o.seconds = std::chrono::duration<double>(Clock::now() - c.start).count();
  o.peak_mb = static_cast<double>(ru.ru_maxrss) / 1024.0;
  int exec_errno = 0;
  const bool exec_failed = read(c.exec_errno_fd, &exec_errno, sizeof exec_errno) == sizeof exec_errno;
  close(c.exec_errno_fd);
  const fs::path dir = s.out / "runs" / c.id;
  const std::string err = slurp(dir / "igm.err");
  // (under an address-space limit the loader may fail to map a shared library, a thread its stack)
  const bool memory_words = has(err, "bad_alloc") || has(err, "Cannot allocate memory") ||
                            (has(err, "unsupported") && has(err, "memory limit")) ||
                            (s.memory_mb > 0 && (has(err, "failed to map segment") ||
                                                 has(err, "Resource temporarily unavailable")));
  if (status != -1 && WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  if (status != -1 && WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (c.timed_out) {
    o.verdict = "timeout";
  } else if (exec_failed) {
    o.verdict = exec_errno == ENOMEM || exec_errno == E2BIG ? "out_of_memory" : "crashed";
    o.error_kind = "exec";
    o.error = std::string("cannot start igm run: ") + std::strerror(exec_errno);
  } else if (memory_words || (o.signal && *o.signal == SIGKILL) ||
             (s.memory_mb > 0 && o.signal && slurp(dir / "igm.log").empty())) {  // could not start within it
    o.verdict = "out_of_memory";
    if (o.exit_code == 2) parse_run_error(err, c.key, o);
  } else if (o.exit_code == 0 || o.exit_code == 1) {
    o.verdict = *o.exit_code == 0 ? "certified" : "rejected";
  } else if (o.exit_code == 2) {
    o.verdict = "invalid_input";
    parse_run_error(err, c.key, o);
  } else {
    o.verdict = "crashed";
    if (o.exit_code == 3) {
      o.error_kind = "internal";
      const auto at = err.rfind("igm: ");
      o.error = at == std::string::npos ? "" : err.substr(at + 5, err.find('\n', at) - at - 5);
    }
  }
  if (o.exit_code == 0 || o.exit_code == 1) {
    if (std::optional<Json> cert = parse_json(slurp(dir / (fs::path(c.key).stem().string() + ".cert.json")))) {
      o.sj_median = cert->number_at({"quality", "quads", "sj_median"});
      o.sj_below_half = cert->number_at({"quality", "quads", "sj_below_half"});
      o.quads = cert->number_at({"stats", "quads"});
      const auto raised = [](const Json* j) {
        const Json* b = j ? j->get("raised_by_floor") : nullptr;
        return b && b->type == Json::Type::Bool && b->boolean;
      };
      o.raised_by_floor = raised(cert->get("stats"));
      if (const Json* surfaces = cert->get("surfaces"))
        for (const Json& one : surfaces->items) o.raised_by_floor = o.raised_by_floor || raised(&one);
    }
  }
  return o;
}

std::string number(double x, int digits) {
  if (!std::isfinite(x)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string json_line(const Child& c, const Outcome& o) {
  const auto opt_int = [](const std::optional<int>& v) { return v ? std::to_string(*v) : std::string("null"); };
  std::string l = "{\"file\": " + json_quote(c.key) + ", \"id\": " + json_quote(c.id) +
                  ", \"verdict\": " + json_quote(o.verdict) + ", \"exit\": " + opt_int(o.exit_code) +
                  ", \"signal\": " + opt_int(o.signal);
  if (!o.error_kind.empty())
    l += ", \"error_kind\": " + json_quote(o.error_kind) + ", \"error\": " + json_quote(o.error);
  l += ", \"seconds\": " + number(o.seconds, 3) + ", \"peak_mb\": " + number(o.peak_mb, 1);
  if (o.quads) l += ", \"quads\": " + number(*o.quads, 0) + ", \"raised_by_floor\": " + (o.raised_by_floor ? "true" : "false");
  if (o.sj_median || o.sj_below_half) {
    l += ", \"quality\": {";
    if (o.sj_median) l += "\"sj_median\": " + number(*o.sj_median, 6);
    if (o.sj_median && o.sj_below_half) l += ", ";
    if (o.sj_below_half) l += "\"sj_below_half\": " + number(*o.sj_below_half, 6);
    l += "}";
  }
  return l + "}\n";
}

// One write() on an O_APPEND descriptor: concurrent batches never interleave within a line.
void append_line(int fd, const std::string& line) {
  const ssize_t n = write(fd, line.data(), line.size());
  if (n != static_cast<ssize_t>(line.size()))
    throw std::runtime_error(std::string("cannot append to results.jsonl: ") + std::strerror(errno));
}

struct Progress {
  bool tty = isatty(STDERR_FILENO) != 0;
  std::size_t total = 0, done = 0;
  std::map<std::string, std::size_t> counts;
  Clock::time_point start = Clock::now();

  Clock::time_point drawn;

  void finished(const Child& c, const Outcome& o) {
    ++done;
    ++counts[o.verdict];
    if (!tty) {
      std::fprintf(stderr, "[batch] %zu/%zu %-13s %8.2f s  %s\n", done, total, o.verdict.c_str(), o.seconds,
                   c.key.c_str());
      return;
    }
    draw();
  }
  // The bar again for the elapsed time, at most once a second (terminal only).
  void tick() {
    if (tty && done < total && Clock::now() - drawn >= std::chrono::seconds(1)) draw();
  }
  void draw() {
    drawn = Clock::now();
    constexpr int kWidth = 30;
    const int filled = total ? static_cast<int>(kWidth * done / total) : kWidth;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kWidth, '.');
    std::string tally;
    for (const char* v : kVerdicts)
      if (counts[v]) tally += std::string(" ") + v + " " + std::to_string(counts[v]);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    std::fprintf(stderr, "\r\033[K[%s] %zu/%zu%s  %.0f s", bar.c_str(), done, total, tally.c_str(), elapsed);
    if (done == total) std::fprintf(stderr, "\n");
    std::fflush(stderr);
  }
};

// Nearest-rank quantile q in [0, 1] of sorted values.
double quantile(const std::vector<double>& sorted, double q) {
  const auto n = sorted.size();
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  return sorted[std::min(n - 1, rank == 0 ? 0 : rank - 1)];
}

void print_quantiles(const char* name, std::vector<double> v, int digits) {
  if (v.empty()) return;
  std::sort(v.begin(), v.end());
  std::printf("%-14s %10s %10s %10s %10s %10s  (%zu meshes)\n", name, number(v.front(), digits).c_str(),
              number(quantile(v, 0.5), digits).c_str(), number(quantile(v, 0.9), digits).c_str(),
              number(quantile(v, 0.99), digits).c_str(), number(v.back(), digits).c_str(), v.size());
}

// The summary of `records` (the last line of each file, restricted to `job` unless empty).
void print_summary(const std::vector<Json>& records, const std::vector<std::string>& job, const fs::path& file) {
  std::map<std::string, const Json*> last;
  for (const Json& r : records) last[r.string_of("file")] = &r;
  if (!job.empty()) {
    std::map<std::string, const Json*> only;
    for (const std::string& k : job)
      if (auto it = last.find(k); it != last.end()) only.insert(*it);
    last.swap(only);
  }
  std::map<std::string, std::size_t> counts;
  std::vector<double> seconds, sj_median, sj_below;
  for (const auto& [key, r] : last) {
    ++counts[r->string_of("verdict")];
    if (auto s = r->number_at({"seconds"})) seconds.push_back(*s);
    if (auto q = r->number_at({"quality", "sj_median"})) sj_median.push_back(*q);
    if (auto q = r->number_at({"quality", "sj_below_half"})) sj_below.push_back(*q);
  }
  std::printf("summary of %zu meshes (%s)\n", last.size(), file.string().c_str());
  for (const char* v : kVerdicts) std::printf("  %-14s %6zu\n", v, counts[v]);
  for (const auto& entry : counts) {  // not a structured binding: the lambda captures it (clang 14)
    const std::string& v = entry.first;
    if (std::find_if(std::begin(kVerdicts), std::end(kVerdicts), [&](const char* k) { return v == k; }) ==
        std::end(kVerdicts))
      std::printf("  %-14s %6zu\n", v.c_str(), entry.second);
  }
  if (!seconds.empty() || !sj_median.empty() || !sj_below.empty())
    std::printf("%-14s %10s %10s %10s %10s %10s\n", "", "min", "median", "p90", "p99", "max");
  print_quantiles("seconds", seconds, 3);
  print_quantiles("sj_median", sj_median, 4);
  print_quantiles("sj_below_half", sj_below, 4);
}

// Waits until a child may have ended (SIGCHLD, blocked by the caller) or the earliest deadline
// passes, at most 1 s.
void wait_for_child(const std::vector<Child>& running) {
  auto wait = std::chrono::duration<double>(1.0);
  const auto now = Clock::now();
  for (const Child& c : running)
    if (c.has_deadline && !c.timed_out) wait = std::min<std::chrono::duration<double>>(wait, c.deadline - now);
  if (wait.count() <= 0) return;
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  const double secs = wait.count();
  timespec ts{static_cast<time_t>(secs), static_cast<long>((secs - std::floor(secs)) * 1e9)};
  sigtimedwait(&chld, nullptr, &ts);
}

bool parse_number(std::string_view s, double& out) {
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size() && std::isfinite(out);
}

}  // namespace

int batch_command(const std::vector<std::string_view>& args) {
  Settings s;
  std::string input;
  bool have_out = false, summary_only = false;
  for (std::size_t i = 0; i < args.size(); ++i) {  // bound: one argument or two per round
    const std::string_view a = args[i];
    if (a == "--") {
      for (std::size_t k = i + 1; k < args.size(); ++k) s.run_options.emplace_back(args[k]);
      break;
    }
    if (a == "--summary") {
      summary_only = true;
    } else if (a == "-o" || a == "-j" || a == "--timeout" || a == "--memory-mb") {
      if (i + 1 >= args.size()) return usage(std::string(a) + " needs a value");
      const std::string_view v = args[++i];
      double x = 0;
      if (a == "-o") {
        s.out = std::string(v);
        have_out = !v.empty();
      } else if (!parse_number(v, x)) {
        return usage(std::string(a) + " needs a number, got '" + std::string(v) + "'");
      } else if (a == "-j") {
        if (x < 1 || x > 256 || x != std::floor(x)) return usage("-j must be an integer in 1..256");
        s.jobs = static_cast<int>(x);
      } else if (a == "--timeout") {
        if (x < 0 || x > 1e7) return usage("--timeout must be in 0..1e7 seconds");
        s.timeout = x;
      } else {
        if (x < 1 || x > static_cast<double>(1LL << 40) || x != std::floor(x))
          return usage("--memory-mb must be an integer in 1..2^40");
        s.memory_mb = static_cast<long long>(x);
      }
    } else if (!a.empty() && a[0] == '-') {
      return usage("unknown option '" + std::string(a) + "' (options of igm run go after --)");
    } else {
      if (!input.empty()) return usage("batch takes one DIR, LIST or MESH (several: a LIST, or GNU parallel)");
      input = std::string(a);
    }
  }
  if (!have_out) return usage("batch needs -o OUT");
  for (const std::string& o : s.run_options)
    if (o == "-o") return usage("the output folder of each run is OUT/runs/ID: no -o after --");
  const fs::path results = s.out / "results.jsonl";
  if (summary_only) {
    if (!input.empty()) return usage("--summary takes no input");
    print_summary(read_results(results), {}, results);
    return kExitOk;
  }
  if (input.empty()) return usage("batch needs a DIR, LIST or MESH");
  try {
    std::error_code ec;
    fs::create_directories(s.out, ec);
    if (ec) throw std::runtime_error("cannot create " + s.out.string() + ": " + ec.message());
    const std::vector<std::string> job = collect(input, s.out);
    const bool one_mesh = !fs::is_directory(input) && is_mesh_path(input);
    std::set<std::string> done;
    for (const Json& r : read_results(results)) done.insert(r.string_of("file"));
    std::vector<std::string> todo;
    for (const std::string& k : job)
      if (!done.count(k)) todo.push_back(k);
    const int fd = open(results.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw std::runtime_error("cannot open " + results.string() + ": " + std::strerror(errno));
    Progress progress;
    progress.total = todo.size();
    if (!one_mesh)
      std::fprintf(stderr, "[batch] %zu meshes, %zu done already, %zu to run, %d at once\n", job.size(),
                   job.size() - todo.size(), todo.size(), s.jobs);
    // SIGCHLD stays pending (blocked) so that wait_for_child wakes as soon as a child ends.
    sigset_t chld;
    sigemptyset(&chld);
    sigaddset(&chld, SIGCHLD);
    sigprocmask(SIG_BLOCK, &chld, nullptr);
    std::vector<Child> running;
    std::size_t next = 0;
    // Bound: each round starts a mesh, reaps one, kills one past its deadline, or waits (at most
    // 1 s) for a child to end; every child ends by itself or is killed at its deadline (without
    // --timeout, when it ends).
    while (next < todo.size() || !running.empty()) {
      bool acted = false;
      while (next < todo.size() && running.size() < static_cast<std::size_t>(s.jobs)) {
        running.push_back(start(todo[next++], s));
        acted = true;
      }
      for (std::size_t k = 0; k < running.size();) {
        Child& c = running[k];
        int status = 0;
        rusage ru{};
        const pid_t r = wait4(c.pid, &status, WNOHANG, &ru);
        if (r < 0 && errno != EINTR) status = -1;  // cannot happen (our own child): counted as crashed
        if (r == c.pid || status == -1) {
          const Outcome o = classify(c, status, ru, s);
          append_line(fd, json_line(c, o));
          progress.finished(c, o);
          running.erase(running.begin() + static_cast<std::ptrdiff_t>(k));
          acted = true;
          continue;
        }
        if (c.has_deadline && !c.timed_out && Clock::now() >= c.deadline) {
          kill(-c.pid, SIGKILL);
          c.timed_out = true;
          acted = true;
        }
        ++k;
      }
      if (!acted) {
        wait_for_child(running);
        progress.tick();
      }
    }
    close(fd);
    if (!one_mesh) print_summary(read_results(results), job, results);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "igm batch: %s\n", e.what());
    return kExitUsage;
  }
  return kExitOk;
}

}  // namespace igm_cli
