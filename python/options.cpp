// Switch strings and keywords -> the pipeline's Plan. A switch string goes
// through the command line's parser (so it means what it means there);
// keywords set the plan's fields directly, with the command line's checks.
#include <cctype>
#include <cmath>
#include <iterator>
#include <optional>
#include <string_view>

#include "bindings.hpp"

namespace deltamesh::python {

namespace {

// Options

// Long options that make sense without files (the rest name outputs).
constexpr std::string_view kLongOptions[] = {"--cdt",
                                             "--fill",
                                             "--strict",
                                             "--steiner",
                                             "--encroachment",
                                             "--order",
                                             "--time-limit",
                                             "--min-angle",
                                             "--max-area",
                                             "--steiner-budget",
                                             "--quality",
                                             "--regional-area",
                                             "--conforming-delaunay",
                                             "--no-boundary-steiner",
                                             "--second-order",
                                             "--convex-hull",
                                             "--regional-attributes",
                                             "--ignore-holes",
                                             "--jettison",
                                             "--edges",
                                             "--neighbors",
                                             "--check",
                                             "--quiet",
                                             "--verbose",
                                             "--zero-based",
                                             "--poly",
                                             "--refine",
                                             "--no-markers",
                                             "--no-poly",
                                             "--no-iteration",
                                             "--incremental",
                                             "--sweepline",
                                             "--vertical-cuts",
                                             "--no-exact",
                                             "--split-segments"};

// Triangle switches refused: -h prints help and would end a program.
std::optional<std::string> refused_switch(char c) {
  if (c == 'h') return std::string("-h prints the command line help: see help(deltamesh.triangulate)");
  return std::nullopt;
}

// Switches Triangle accepts that change nothing here: a Python warning
// names each (the call still runs, as with Triangle).
const char* no_effect_reason(char c) {
  switch (c) {
    case 'i':
    case 'F':
    case 'l':
      return "it picks Triangle's Delaunay algorithm; deltamesh has its own and the triangulation is the same";
    case 'X':
      return "deltamesh always uses exact predicates";
    case 's':
      return "segments are always inserted by constrained Delaunay triangulation";
    case 'u':
      return "Triangle's compiled-in triunsuitable() does not exist here: pass max_area_fn=f(x, y)";
    case 'g':
      return "no .off file is written: use deltamesh.write(mesh, 'out.off')";
    case 'I':
      return "there are no output files, hence no iteration numbers";
    default:
      return nullptr;
  }
}

// A long option triangulate() does not take: the command line's that are
// about files, or a misspelling (named as such, the nearest one suggested).
std::string unavailable_long_option(const std::string& name, const std::string& opts) {
  const std::vector<std::string_view> cli = long_option_names();
  if (std::find(cli.begin(), cli.end(), name) != cli.end())
    return "option " + name + " in '" + opts + "' is not available in deltamesh.triangulate (it is about files)";
  const std::vector<std::string_view> known(std::begin(kLongOptions), std::end(kLongOptions));
  std::string msg = unknown_option_message(name, known);
  const std::string_view cli_hint = " (see deltamesh --help)";
  if (ends_with(msg, cli_hint)) msg.resize(msg.size() - cli_hint.size());
  return "bad switches '" + opts + "': " + msg;
}

void warn_no_effect(char c) {
  const std::string msg = std::string("deltamesh: switch -") + c + " has no effect: " + no_effect_reason(c);
  if (PyErr_WarnEx(PyExc_UserWarning, msg.c_str(), 3) < 0) throw py::error_already_set();
}

}  // namespace

// Parses a Triangle switch string ("pq30a0.1", a leading '-' optional) with
// the command line's parser; whitespace separates it from long options given as
// --name=value. Throws ValueError for anything the parser rejects.
CommandLine parse_switches(const std::string& opts) {
  std::vector<std::string> args;
  std::size_t i = 0;
  while (i < opts.size()) {
    while (i < opts.size() && std::isspace(static_cast<unsigned char>(opts[i]))) ++i;
    std::size_t j = i;
    while (j < opts.size() && !std::isspace(static_cast<unsigned char>(opts[j]))) ++j;
    if (j > i) {
      std::string tok = opts.substr(i, j - i);
      if (tok.rfind("--", 0) == 0) {
        const std::string name = tok.substr(0, tok.find('='));
        if (name == "--adapt" || name == "--smooth")
          throw py::value_error("option " + name + " in '" + opts +
                                "': use deltamesh.adapt(mesh, size, opts, smooth=N) (smooth=0 for none)");
        if (std::find(std::begin(kLongOptions), std::end(kLongOptions), name) == std::end(kLongOptions))
          throw py::value_error(unavailable_long_option(name, opts));
      } else {
        if (tok[0] == '-') tok.erase(0, 1);
        if (tok.empty()) {
          i = j;
          continue;
        }
        // Numbers are digits and '.', so every letter is a switch.
        for (const char c : tok)
          if (auto why = refused_switch(c)) throw py::value_error("switch " + *why);
        tok = "-" + tok;
      }
      args.push_back(std::move(tok));
    }
    i = j;
  }
  try {
    // One at a time first, so that "--cdt" without "=value" cannot take the next token as its value.
    for (const std::string& a : args) (void)parse_arguments({a});
    CommandLine o = parse_arguments(args);
    for (const std::string& u : o.unavailable)
      if (u.rfind("-u", 0) != 0) throw py::value_error("switch " + u + " is not available");
    std::string warned;
    for (const std::string& a : args) {
      if (a.rfind("--", 0) == 0) continue;
      for (std::size_t k = 1; k < a.size(); ++k) {
        const char c = a[k];
        if (no_effect_reason(c) && warned.find(c) == std::string::npos) {
          warned += c;
          warn_no_effect(c);
        }
      }
    }
    return o;
  } catch (const UsageError& e) {
    std::string msg = e.what();
    const std::string_view cli_hint = " (see deltamesh --help)";
    if (ends_with(msg, cli_hint)) msg.resize(msg.size() - cli_hint.size());
    throw py::value_error("bad switches '" + opts + "': " + msg);
  }
}

// The keyword form, as long options for the same parser: each keyword is

namespace {

// A value keyword given as a string is read as the command line reads its
// long option; a number is checked the same way. Errors name the keyword.
void string_value(CommandLine& cl, const char* kw, const char* option, const std::string& text) {
  try {
    apply_long_option(cl, option, text);
  } catch (const UsageError& e) {
    throw py::value_error(std::string(kw) + ": " + e.what());
  }
}

// The number a keyword holds, or nullopt for a string (read as above).
// `text` receives how the number reads (for messages).
std::optional<double> number_value(const char* kw, py::handle v, std::string& text) {
  if (py::isinstance<py::str>(v)) return std::nullopt;
  if (py::isinstance<py::bool_>(v)) throw py::value_error(std::string(kw) + ": expected a number or a string, got a bool");
  if (py::isinstance<py::int_>(v)) {
    text = py::str(v).cast<std::string>();
    return v.cast<double>();
  }
  try {
    const double x = v.cast<double>();
    text = number_text(x);
    return x;
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(kw) + ": expected a number or a string, got " +
                          py::str(py::type::of(v)).cast<std::string>());
  }
}

[[noreturn]] void bad_number(const char* kw, const char* option, const std::string& text, const char* rule) {
  throw py::value_error(std::string(kw) + ": " + option + "=" + text + ": " + rule);
}

}  // namespace

Plan keyword_plan(const Keywords& k) {
  CommandLine cl;  // for string values, read by the command line's rules
  Plan& p = cl.plan;
  std::string text;
  if (given(k.min_angle)) {
    if (auto x = number_value("min_angle", k.min_angle, text)) {
      if (!std::isfinite(*x)) bad_number("min_angle", "--min-angle", text, "degrees, a number");
      p.refine.quality = true;
      p.refine.min_angle = *x;
    } else {
      string_value(cl, "min_angle", "--min-angle", k.min_angle.cast<std::string>());
    }
  }
  if (given(k.max_area)) {
    if (auto x = number_value("max_area", k.max_area, text)) {
      if (!(*x > 0) || !std::isfinite(*x))
        bad_number("max_area", "--max-area", text, "the maximum area must be a positive number");
      p.refine.max_area = *x;
    } else {
      string_value(cl, "max_area", "--max-area", k.max_area.cast<std::string>());
    }
  }
  p.refine.input_area_bounds = k.regional_area;
  if (given(k.max_steiner)) {
    if (auto x = number_value("max_steiner", k.max_steiner, text)) {
      // A whole number of points that fits 64 bits.
      if (!(*x >= 0 && *x < 18446744073709551616.0 && std::floor(*x) == *x) ||
          text.find_first_not_of("0123456789") != std::string::npos)
        bad_number("max_steiner", "--steiner-budget", text, "a count of Steiner points");
      p.refine.steiner_budget = py::isinstance<py::int_>(k.max_steiner)
                                    ? k.max_steiner.cast<unsigned long long>()
                                    : static_cast<unsigned long long>(*x);
    } else {
      string_value(cl, "max_steiner", "--steiner-budget", k.max_steiner.cast<std::string>());
    }
  }
  p.refine.conforming_delaunay = k.conforming_delaunay;
  if (k.segment_splitting == "interior") p.refine.no_boundary_steiner = 1;
  else if (k.segment_splitting == "none") p.refine.no_boundary_steiner = 2;
  else if (k.segment_splitting != "all")
    throw py::value_error("segment_splitting: '" + k.segment_splitting +
                          "' must be 'all', 'interior' (Triangle's -Y) or 'none' (-YY)");
  p.domain.convex_hull = k.convex_hull;
  p.domain.regional_attributes = k.regional_attributes;
  p.domain.ignore_holes = k.ignore_holes;
  string_value(cl, "fill", "--fill", k.fill);
  string_value(cl, "cdt", "--cdt", k.cdt);
  p.strict = k.strict;
  string_value(cl, "steiner", "--steiner", k.steiner);
  string_value(cl, "encroachment", "--encroachment", k.encroachment);
  string_value(cl, "order", "--order", k.order);
  if (given(k.time_limit)) {
    if (auto x = number_value("time_limit", k.time_limit, text)) {
      if (!(*x > 0)) bad_number("time_limit", "--time-limit", text, "seconds, a positive number");
      p.refine.time_limit = *x;
    } else {
      string_value(cl, "time_limit", "--time-limit", k.time_limit.cast<std::string>());
    }
  }
  p.jettison = k.jettison;
  if (k.second_order) p.order = 2;
  p.edges = k.edges;
  p.neighbors = k.neighbors;
  p.check = k.check;
  p.markers = k.markers;
  p.quiet = k.quiet;
  // Segments (or triangles) mean 'p'; triangles mean 'r'.
  const bool poly = k.segments || k.triangles;
  p.input = k.triangles ? InputKind::Mesh : poly ? InputKind::Pslg : InputKind::Points;
  p.mesh_segments = k.triangles && poly;
  return p;
}

}  // namespace deltamesh::python
