// Triangle's switch strings and the long options, parsed into a CommandLine.
#include "deltamesh/switches.hpp"

#include "deltamesh/errors.hpp"
#include "deltamesh/formats.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <charconv>

#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

#include "core/float_chars.hpp"

namespace deltamesh {

namespace {

// A switch string is Triangle's: letters, each optionally followed by a
// number with no space (-pq30.5a0.01zQ). Numbers are digits and '.' only, so
// a letter that follows a number (like the 'e' in -a0.1e) is the next switch.
class SwitchString {
 public:
  SwitchString(std::string_view s, CommandLine& o) : s_(s), o_(o) {}

  void parse() {
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      switch (c) {
        case 'p': o_.poly = true; break;
        case 'r': o_.refine = true; break;
        case 'c': o_.plan.domain.convex_hull = true; break;
        case 'A': o_.plan.domain.regional_attributes = true; break;
        case 'O': o_.plan.domain.ignore_holes = true; break;
        case 'P': o_.no_poly = true; break;
        case 'z': o_.plan.zero_based = true; break;
        case 'Q': o_.plan.quiet = true; break;
        case 'V': ++o_.plan.verbose; break;
        case 'C': o_.plan.check = true; break;
        case 'N': o_.no_node = true; break;
        case 'E': o_.no_ele = true; break;
        case 'I': o_.no_iteration = true; break;
        case 'j': o_.plan.jettison = true; break;
        case 'e': o_.plan.edges = true; break;
        case 'n': o_.plan.neighbors = true; break;
        case 'B': o_.plan.markers = false; break;
        case 'h': o_.help = true; break;
        case 'i': case 'F': case 'l': case 'X': case 's':  // accepted: mapped to ours, a note with -V
          if (std::find(o_.compat_notes.begin(), o_.compat_notes.end(), c) == o_.compat_notes.end())
            o_.compat_notes.push_back(c);
          break;
        case 'q': {
          o_.plan.refine.quality = true;
          const std::string_view num = number();
          if (!num.empty()) o_.plan.refine.min_angle = to_double(c, num);
          break;
        }
        case 'a': {
          
          const std::string_view num = number();
          if (num.empty()) {
            o_.plan.refine.input_area_bounds = true;
          } else {
            o_.plan.refine.max_area = to_double(c, num);
            if (!(*o_.plan.refine.max_area > 0))
              throw UsageError{"-a" + std::string(num) + ": the maximum area must be positive"};
          }
          break;
        }
        case 'S': {
          const std::string_view num = digits();
          unsigned long long n = 0;
          if (!num.empty()) {
            const auto r = std::from_chars(num.data(), num.data() + num.size(), n);
            if (r.ec != std::errc() || r.ptr != num.data() + num.size())
              throw UsageError{"-S" + std::string(num) + ": the Steiner point budget is too large"};
          }
          o_.plan.refine.steiner_budget = n;
          break;
        }
        case 'o': {
          if (i_ >= s_.size() || s_[i_] != '2')
            throw UsageError{"switch -o must be followed by 2 (-o2: second-order, six-node triangles)"};
          ++i_;
          o_.plan.order = 2;
          break;
        }
        case 'Y':
          ++o_.plan.refine.no_boundary_steiner;
          break;
        case 't': {  // not one of Triangle's letters
          const std::string_view num = digits();
          if (num.empty()) throw UsageError{"switch -t needs a thread count (-t4, or -t 4; 0: every hardware thread)"};
          o_.plan.threads = thread_count("-t" + std::string(num), num);
          break;
        }
        // -u: Triangle calls a function compiled into it; here that is the
        // API's RefineOptions::max_area_at / max_edge_at callback.
        case 'u': planned(c, {}, "user size function: the C++ API's RefineOptions::max_area_at"); break;
        case 'D': o_.plan.refine.conforming_delaunay = true; break;
        case 'v': o_.voronoi = true; break;
        case 'g': o_.geomview = true; break;
        default:
          if (std::isdigit(static_cast<unsigned char>(c)) || c == '.')
            throw UsageError{std::string("number '") + c + "' in '-" + std::string(s_) +
                             "' does not follow a switch that takes one (q, a, S, t)"};
          throw UsageError{std::string("unknown switch -") + c + " in '-" + std::string(s_) +
                           "' (see deltamesh --help)"};
      }
    }
  }

 private:
  // The run of digits and '.' at the current position (possibly empty).
  // Triangle's numbers have no exponent: an 'e' followed by a digit or a
  // sign and a digit (-pa1e-3) is refused with the number to type instead
  // (a lone 'e' after a number is still the edges switch: -a0.1e).
  std::string_view number() {
    const std::size_t start = i_;
    while (i_ < s_.size() && (std::isdigit(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.')) ++i_;
    refuse_exponent(start);
    return s_.substr(start, i_ - start);
  }
  void refuse_exponent(std::size_t start) const {
    if (i_ == start || i_ >= s_.size() || (s_[i_] != 'e' && s_[i_] != 'E')) return;
    std::size_t k = i_ + 1;
    if (k < s_.size() && (s_[k] == '-' || s_[k] == '+')) ++k;
    if (k >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[k]))) return;
    while (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) ++k;
    exponent_error(start, k);
  }
  [[noreturn]] void exponent_error(std::size_t start, std::size_t end) const {
    const char c = start > 0 ? s_[start - 1] : '?';
    const std::string written(s_.substr(start, end - start));
    std::string plain = written;
    char* stop = nullptr;
    const double v = std::strtod(written.c_str(), &stop);
    if (stop && *stop == '\0' && std::isfinite(v)) {
      char buf[400];  // the shortest fixed-point form that reads back as v
      const auto r = chars::shortest_fixed(buf, buf + sizeof buf, v);
      if (r.ec == std::errc()) plain.assign(buf, r.ptr);
    }
    throw UsageError{std::string("-") + c + written + " in '-" + std::string(s_) +
                     "': switch numbers have no exponent (Triangle's syntax: digits and '.'); type -" + c + plain};
  }
  std::string_view digits() {
    const std::size_t start = i_;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
    refuse_exponent(start);
    return s_.substr(start, i_ - start);
  }
  static double to_double(char c, std::string_view num) {
    double v = 0;
    const auto r = chars::parse_double(num.data(), num.data() + num.size(), v);
    if (r.ec != std::errc() || r.ptr != num.data() + num.size() || !std::isfinite(v))
      throw UsageError{std::string("-") + c + std::string(num) + ": '" + std::string(num) + "' is not a number"};
    return v;
  }
  static unsigned thread_count(const std::string& what, std::string_view num) {
    unsigned n = 0;
    const auto r = std::from_chars(num.data(), num.data() + num.size(), n);
    if (num.empty() || r.ec != std::errc() || r.ptr != num.data() + num.size() || n > 4096)
      throw UsageError{what + ": a thread count from 0 (every hardware thread) to 4096"};
    return n;
  }

 public:
  static unsigned parse_thread_count(const std::string& what, std::string_view num) { return thread_count(what, num); }

 private:
  void planned(char c, std::string_view num, const char* what) {
    o_.unavailable.push_back(std::string("-") + c + std::string(num) + " (" + what + ")");
  }

  std::string_view s_;
  CommandLine& o_;
  std::size_t i_ = 0;
};

// Long options that take a value (--smooth's is optional: parsed apart).
bool is_value_option(std::string_view name);

// Long options that take no value (--smooth's is optional).
constexpr std::string_view kFlagNames[] = {
    "--help", "--version", "--strict", "--quiet", "--verbose", "--check", "--zero-based", "--jettison",
    "--edges", "--neighbors", "--no-node", "--no-ele", "--no-poly", "--no-iteration", "--no-markers",
    "--convex-hull", "--regional-attributes", "--ignore-holes", "--vtu-binary", "--geojson-segments",
    "--voronoi-overlay", "--poly", "--refine", "--adapt", "--quality", "--regional-area", "--user-area",
    "--conforming-delaunay", "--voronoi", "--off", "--second-order", "--no-boundary-steiner", "--incremental",
    "--sweepline", "--vertical-cuts", "--no-exact", "--split-segments", "--smooth", "--overwrite"};
constexpr std::string_view kValueNames[] = {
    "--svg",   "--trace",   "--output",   "--msh-version",    "--region-property", "--area-property",
    "--min-angle", "--max-area", "--steiner-budget", "--cdt",            "--steiner",
    "--encroachment", "--order", "--time-limit",    "--stats",           "--fill", "--threads"};

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

UsageError unknown_option(const std::string& name) {
  return UsageError{unknown_option_message(name, long_option_names())};
}

bool is_value_option(std::string_view name) {
  return std::find(std::begin(kValueNames), std::end(kValueNames), name) != std::end(kValueNames);
}

bool is_flag_option(std::string_view name) {
  return std::find(std::begin(kFlagNames), std::end(kFlagNames), name) != std::end(kFlagNames);
}

}  // namespace

std::string unknown_option_message(std::string_view name, const std::vector<std::string_view>& known) {
  std::string_view best;
  std::size_t best_d = name.size() / 3 + 1;
  for (std::string_view k : known) {
    const std::size_t d = edit_distance(name, k);
    if (d < best_d) best_d = d, best = k;
  }
  if (best.empty()) return "unknown option " + std::string(name) + " (see deltamesh --help)";
  return "unknown option " + std::string(name) + " (did you mean " + std::string(best) + "?)";
}

std::vector<std::string_view> long_option_names() {
  std::vector<std::string_view> names(std::begin(kFlagNames), std::end(kFlagNames));
  names.insert(names.end(), std::begin(kValueNames), std::end(kValueNames));
  return names;
}

std::optional<FillRule> parse_fill_rule(std::string_view v) {
  if (v == "holes") return FillRule::Holes;
  if (v == "evenodd" || v == "even-odd") return FillRule::EvenOdd;
  return std::nullopt;
}

std::optional<RefineOrder> parse_refine_order(std::string_view v) {
  if (v == "shortest") return RefineOrder::ShortestEdgeFirst;
  if (v == "worst") return RefineOrder::WorstFirst;
  return std::nullopt;
}

void apply_long_option(CommandLine& cl, std::string_view name_view, std::string_view value) {
  const std::string name(name_view);
  if (name == "--svg") {
    cl.svg_path = std::string(value);
  } else if (name == "--trace") {
    cl.trace_path = std::string(value);
  } else if (name == "--output") {
    const std::string v = std::string(value);
    if (!output_format_for(v))
      throw UsageError{"--output " + v +
                       ": cannot tell the format from the extension (known: .msh .vtu .vtk .svg .geojson .json "
                       ".off .node .ele .edge .neigh .poly)"};
    cl.outputs.push_back(v);
  } else if (name == "--msh-version") {
    const std::string v = std::string(value);
    cl.msh_version_given = true;
    if (v == "2.2") cl.msh_v22 = true;
    else if (v == "4.1" || v == "4") cl.msh_v22 = false;
    else throw UsageError{"--msh-version=" + v + ": the version must be 2.2 or 4.1"};
  } else if (name == "--region-property") {
    cl.region_property = std::string(value);
  } else if (name == "--area-property") {
    cl.area_property = std::string(value);
  } else if (name == "--min-angle") {
    cl.plan.refine.quality = true;
    const std::string v = std::string(value);
    char* end = nullptr;
    const double t = std::strtod(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !std::isfinite(t)) throw UsageError{"--min-angle=" + v + ": degrees, a number"};
    cl.plan.refine.min_angle = t;
  } else if (name == "--max-area") {
    const std::string v = std::string(value);
    char* end = nullptr;
    const double t = std::strtod(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !(t > 0) || !std::isfinite(t))
      throw UsageError{"--max-area=" + v + ": the maximum area must be a positive number"};
    cl.plan.refine.max_area = t;
  } else if (name == "--steiner-budget") {
    const std::string v = std::string(value);
    unsigned long long n = 0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
    if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size())
      throw UsageError{"--steiner-budget=" + v + ": a count of Steiner points"};
    cl.plan.refine.steiner_budget = n;
  } else if (name == "--cdt") {
    const std::string v = std::string(value);
    const std::optional<CdtMethod> m = parse_cdt_method(v);
    if (!m) throw UsageError{"--cdt=" + v + ": the method must be fast, ct, lawson or lifting"};
    cl.plan.method = *m;
  } else if (name == "--steiner") {
    const std::string v = std::string(value);
    const auto r = parse_steiner_rule(v);
    if (!r) throw UsageError{"--steiner=" + v + ": the rule must be best, grid, offcenter or circumcenter"};
    cl.plan.refine.steiner = *r;
  } else if (name == "--encroachment") {
    const std::string v = std::string(value);
    const auto r = parse_encroachment_rule(v);
    if (!r) throw UsageError{"--encroachment=" + v + ": the rule must be lens or circle"};
    cl.plan.refine.encroachment = *r;
  } else if (name == "--order") {
    const std::string v = std::string(value);
    const std::optional<RefineOrder> r = parse_refine_order(v);
    if (!r) throw UsageError{"--order=" + v + ": the order must be shortest or worst"};
    cl.plan.refine.order = *r;
  } else if (name == "--time-limit") {
    const std::string v = std::string(value);
    char* end = nullptr;
    const double t = std::strtod(v.c_str(), &end);
    if (end == v.c_str() || *end != '\0' || !(t > 0)) throw UsageError{"--time-limit=" + v + ": seconds, a positive number"};
    cl.plan.refine.time_limit = t;
  } else if (name == "--stats") {
    // json or json:FILE (a bare --stats never takes the next argument: it
    // would be the input file).
    const std::string v = std::string(value);
    if (v != "json" && v.rfind("json:", 0) != 0)
      throw UsageError{"--stats=" + v + ": the format is json (--stats=json, or --stats=json:FILE to write it to FILE)"};
    if (v.size() > 5) cl.stats_path = v.substr(5);
    else if (v == "json:") throw UsageError{"--stats=json: needs a file name after ':'"};
    cl.stats_json = true;
  } else if (name == "--threads") {
    cl.plan.threads = SwitchString::parse_thread_count("--threads=" + std::string(value), value);
  } else if (name == "--fill") {
    const std::string v = std::string(value);
    const std::optional<FillRule> r = parse_fill_rule(v);
    if (!r) throw UsageError{"--fill=" + v + ": the rule must be holes or evenodd"};
    cl.plan.domain.fill = *r;
  } else {
    throw unknown_option(name);
  }
}

CommandLine parse_arguments(const std::vector<std::string>& args) {
  CommandLine o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const std::string& name) -> std::string {
      const auto eq = a.find('=');
      if (eq != std::string::npos) return a.substr(eq + 1);
      if (i + 1 >= args.size()) throw UsageError{"option " + name + " needs a value"};
      return args[++i];
    };
    auto no_value = [&](const std::string& name) {
      if (a.find('=') != std::string::npos) throw UsageError{"option " + name + " takes no value"};
    };
    if (a.rfind("--", 0) == 0) {
      const std::string name = a.substr(0, a.find('='));
      if (name == "--stats") {
        apply_long_option(o, name, a.find('=') != std::string::npos ? a.substr(a.find('=') + 1) : "json");
      } else if (is_value_option(name)) {
        apply_long_option(o, name, value(name));
      } else if (name == "--smooth") {
        // The count is optional: --smooth alone is 3 passes.
        o.plan.smooth = 3;
        if (a.find('=') != std::string::npos) {
          const std::string v = a.substr(a.find('=') + 1);
          int n = 0;
          const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
          if (v.empty() || r.ec != std::errc() || r.ptr != v.data() + v.size() || n < 0 || n > 1000)
            throw UsageError{"--smooth=" + v + ": a number of passes from 0 to 1000"};
          o.plan.smooth = n;
        }
      } else {
        if (!is_flag_option(name)) throw unknown_option(name);
        no_value(name);
        if (name == "--help") o.help = true;
        else if (name == "--version") o.version = true;
        else if (name == "--strict") o.plan.strict = true;
        else if (name == "--quiet") o.plan.quiet = true;
        else if (name == "--verbose") ++o.plan.verbose;
        else if (name == "--check") o.plan.check = true;
        else if (name == "--zero-based") o.plan.zero_based = true;
        else if (name == "--jettison") o.plan.jettison = true;
        else if (name == "--edges") o.plan.edges = true;
        else if (name == "--neighbors") o.plan.neighbors = true;
        else if (name == "--no-node") o.no_node = true;
        else if (name == "--no-ele") o.no_ele = true;
        else if (name == "--no-poly") o.no_poly = true;
        else if (name == "--no-iteration") o.no_iteration = true;
        else if (name == "--overwrite") o.overwrite = true;
        else if (name == "--no-markers") o.plan.markers = false;
        else if (name == "--convex-hull") o.plan.domain.convex_hull = true;
        else if (name == "--regional-attributes") o.plan.domain.regional_attributes = true;
        else if (name == "--ignore-holes") o.plan.domain.ignore_holes = true;
        else if (name == "--vtu-binary") o.vtu_binary = true;
        else if (name == "--geojson-segments") o.geojson_segments = true;
        else if (name == "--voronoi-overlay") o.voronoi_overlay = true;
        else if (name == "--poly") o.poly = true;
        else if (name == "--refine") o.refine = true;
        else if (name == "--adapt") { o.adapt = true; o.refine = true; }
        else if (name == "--quality") o.plan.refine.quality = true;
        else if (name == "--regional-area") {  o.plan.refine.input_area_bounds = true; }
        else if (name == "--user-area") { o.unavailable.push_back("--user-area (-u: user size function: the C++ API's RefineOptions::max_area_at)"); }
        else if (name == "--conforming-delaunay") o.plan.refine.conforming_delaunay = true;
        else if (name == "--voronoi") o.voronoi = true;
        else if (name == "--off") o.geomview = true;
        else if (name == "--second-order") o.plan.order = 2;
        else if (name == "--no-boundary-steiner") ++o.plan.refine.no_boundary_steiner;
        else if (name == "--incremental" || name == "--sweepline" || name == "--vertical-cuts" ||
                 name == "--no-exact" || name == "--split-segments") {
          const char c = name == "--incremental" ? 'i' : name == "--sweepline" ? 'F' : name == "--vertical-cuts" ? 'l'
                       : name == "--no-exact" ? 'X' : 's';
          if (std::find(o.compat_notes.begin(), o.compat_notes.end(), c) == o.compat_notes.end()) o.compat_notes.push_back(c);
        }
        else throw InternalError("parse_arguments", "flag " + name + " is listed but not handled");
      }
    } else if (a.size() > 1 && a[0] == '-') {
      // "-t 4": a switch string ending in t takes a count from the next argument.
      std::string s = a.substr(1);
      if (s.back() == 't' && i + 1 < args.size() && !args[i + 1].empty() &&
          args[i + 1].find_first_not_of("0123456789") == std::string::npos)
        s += args[++i];
      SwitchString(s, o).parse();
    } else {
      if (!o.input.empty()) throw UsageError{"more than one input file: '" + o.input + "' and '" + a + "'"};
      o.input = a;
    }
  }
  // What is meshed, from -p, -r and --adapt in any order.
  Plan& plan = o.plan;
  plan.input = o.adapt ? InputKind::Adapt : o.refine ? InputKind::Mesh : o.poly ? InputKind::Pslg : InputKind::Points;
  plan.mesh_segments = o.refine && o.poly;
  if (o.plan.smooth > 0 && o.plan.refine.conforming_delaunay)
    throw UsageError{"--smooth cannot be combined with -D: moved vertices may encroach segments"};
  return o;
}

}  // namespace deltamesh
