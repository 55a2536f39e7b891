// JSON serialisation of a certificate (schema in certify/README.md).
#include <cstdio>

#include "certify/certify.h"

namespace igm::certify {

namespace {

// Appends every piece (avoids `"literal" + std::string` temporaries).
template <class... Parts>
void app(std::string& out, const Parts&... parts) {
  (out.append(parts), ...);
}

void put_string(std::string& out, const std::string& s) {
  out.push_back('"');
  for (unsigned char c : s) {  // bound: |s|
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      case '\r': out += "\\r"; break;
      default:
        if (c < 0x20 || c >= 0x7f) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out.push_back(static_cast<char>(c));
        }
    }
  }
  out.push_back('"');
}

std::string opt_int(const std::optional<std::int64_t>& x) {
  return x ? std::to_string(*x) : std::string("null");
}

void put_histogram(std::string& o, const char* key, const std::string& name,
                   const std::map<std::int64_t, std::int64_t>& bins) {
  app(o, ",\n     \"", key, "\": {\"name\": ");
  put_string(o, name);
  o += ", \"bins\": {";
  bool first = true;
  for (const auto& [k, v] : bins) {  // bound: |bins|
    if (!first) o += ", ";
    first = false;
    put_string(o, std::to_string(k));
    app(o, ": ", std::to_string(v));
  }
  o += "}}";
}

// One check's object after its opening brace, through its closing brace.
void put_check(std::string& o, const CheckResult& c) {
  app(o, "\"id\": ", std::to_string(c.id), ", \"name\": ");
  put_string(o, c.name);
  o += ", \"status\": \"";
  o += to_string(c.status);
  o += "\", \"pass\": ";
  o += c.passed() ? "true" : "false";
  o += ",\n     \"counts\": {";
  for (std::size_t k = 0; k < c.counts.size(); ++k) {
    if (k) o += ", ";
    put_string(o, c.counts[k].first);
    o += ": ";
    o += std::to_string(c.counts[k].second);
  }
  o += "}";
  if (!c.histogram_name.empty()) put_histogram(o, "histogram", c.histogram_name, c.histogram);
  if (!c.boundary_histogram_name.empty())
    put_histogram(o, "boundary_histogram", c.boundary_histogram_name, c.boundary_histogram);
  o += ",\n     \"offending\": ";
  o += std::to_string(c.offending);
  o += ", \"witnesses_shown\": ";
  o += std::to_string(c.witnesses.size());
  o += ", \"note\": ";
  put_string(o, c.note);
  o += ",\n     \"witnesses\": [";
  for (std::size_t w = 0; w < c.witnesses.size(); ++w) {  // bound: max_witnesses
    const Witness& x = c.witnesses[w];
    o += w ? ",\n       {" : "\n       {";
    o += "\"kind\": ";
    put_string(o, x.kind);
    o += ", \"ids\": [";
    for (std::size_t j = 0; j < x.ids.size(); ++j) {
      if (j) o += ", ";
      o += std::to_string(x.ids[j]);
    }
    o += "], \"reason\": ";
    put_string(o, x.reason);
    o += ", \"values\": {";
    for (std::size_t j = 0; j < x.values.size(); ++j) {
      if (j) o += ", ";
      put_string(o, x.values[j].first);
      o += ": ";
      put_string(o, x.values[j].second);
    }
    o += "}}";
  }
  o += c.witnesses.empty() ? "]}" : "\n     ]}";
}

}  // namespace

std::string to_json(const Report& r) {
  std::string o;
  o += "{\n  \"certifier\": \"igm-certify\",\n  \"format_version\": 1,\n  \"source\": ";
  put_string(o, r.source);
  o += ",\n  \"mode\": ";
  put_string(o, r.mode);
  o += ",\n  \"verdict\": \"";
  o += to_string(r.verdict);
  o += "\",\n  \"valid\": ";
  o += r.valid() ? "true" : "false";
  o += ",\n  \"exit_code\": ";
  o += std::to_string(exit_code(r));
  o += ",\n  \"index_base\": 0,\n  \"error\": ";
  if (r.verdict == Verdict::Unreadable) {
    o += "{\"message\": ";
    put_string(o, r.error);
    app(o, ", \"line\": ", std::to_string(r.error_line), "}");
  } else {
    o += "null";
  }
  o += ",\n  \"mesh\": {\"vertices\": ";
  o += std::to_string(r.num_vertices);
  o += ", \"edges\": ";
  o += std::to_string(r.num_edges);
  o += ", \"faces\": ";
  o += std::to_string(r.num_faces);
  o += ", \"euler_characteristic\": ";
  o += r.euler_characteristic ? std::to_string(*r.euler_characteristic) : std::string("null");
  o += ", \"genus\": ";
  o += r.genus ? std::to_string(*r.genus) : std::string("null");
  app(o, ", \"boundary_edges\": ", std::to_string(r.num_boundary_edges),
      ", \"boundary_loops\": ", opt_int(r.boundary_loops),
      ", \"connected_components\": ", std::to_string(r.components.size()), "}");
  o += ",\n  \"components\": [";
  for (std::size_t i = 0; i < r.components.size(); ++i) {  // bound: components <= V
    const ComponentInfo& c = r.components[i];
    app(o, i ? ",\n    " : "\n    ", "{\"first_vertex\": ", std::to_string(c.first_vertex),
        ", \"vertices\": ", std::to_string(c.vertices), ", \"edges\": ", std::to_string(c.edges),
        ", \"faces\": ", std::to_string(c.faces));
    app(o, ", \"boundary_edges\": ", std::to_string(c.boundary_edges), ", \"boundary_loops\": ",
        opt_int(c.boundary_loops), ", \"euler_characteristic\": ",
        std::to_string(c.euler_characteristic), ", \"genus\": ", opt_int(c.genus));
    app(o, ", \"poincare_hopf_sum\": ", opt_int(c.poincare_hopf_sum),
        ", \"poincare_hopf_expected\": ", std::to_string(4 * c.euler_characteristic), "}");
  }
  o += r.components.empty() ? "]" : "\n  ]";
  o += ",\n  \"checks\": [";
  for (std::size_t i = 0; i < r.checks.size(); ++i) {  // bound: <= 5 checks
    o += i ? ",\n    {" : "\n    {";
    put_check(o, r.checks[i]);
  }
  o += r.checks.empty() ? "]" : "\n  ]";
  if (r.features) {  // only with Options::feature_edges: without it the bytes are as before
    o += ",\n  \"features\": {";
    put_check(o, *r.features);
  }
  o += "\n}\n";
  return o;
}

std::string summary(const Report& r) {
  std::string s = std::string(r.verdict == Verdict::Valid      ? "VALID"
                              : r.verdict == Verdict::Invalid  ? "INVALID"
                                                               : "UNREADABLE");
  s += " " + r.mode + " " + r.source;
  if (r.verdict == Verdict::Unreadable) return s + ": " + r.error;
  app(s, ": V=", std::to_string(r.num_vertices), " E=", std::to_string(r.num_edges), " F=",
      std::to_string(r.num_faces), " genus=", r.genus ? std::to_string(*r.genus) : std::string("?"));
  if (r.boundary_loops && *r.boundary_loops > 0)
    app(s, " boundary_loops=", std::to_string(*r.boundary_loops));
  if (r.components.size() > 1) app(s, " components=", std::to_string(r.components.size()));
  for (const auto& c : r.checks) {
    app(s, "; ", std::to_string(c.id), ":", c.name, "=", to_string(c.status));
    if (c.offending) app(s, "(", std::to_string(c.offending), ")");
  }
  if (r.features) {
    app(s, "; features=", to_string(r.features->status), " ", std::to_string(r.features->count("edges_on_isoline")),
        "/", std::to_string(r.features->count("edges_checked")), " on isolines");
  }
  return s;
}

}  // namespace igm::certify
