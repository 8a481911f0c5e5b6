// What the page's worker calls (web/worker.js): run the command line on
// files in the in-memory file system, then load the mesh it wrote for
// drawing. Reading back the written .node/.ele (the library's readers) keeps
// one path from switches to files: the picture is the files the user downloads.
#include <emscripten/emscripten.h>

#include <cstdio>
#include <string>
#include <vector>

#include "core/angles.hpp"
#include "deltamesh/deltamesh.hpp"

int deltamesh_cli_main(int argc, char** argv);  // cli_entry.cpp

namespace {

struct View {
  std::vector<double> xy;           // 2 per vertex
  std::vector<int> triangles;       // 3 per triangle, 0-based
  std::vector<double> min_angle;    // per triangle, degrees
  std::vector<int> segments;        // 2 per segment, 0-based
  std::string error;
};
View view;

}  // namespace

extern "C" {

// `args`: the command line's arguments, one per line. Returns its exit code.
EMSCRIPTEN_KEEPALIVE int dm_run(const char* args) {
  std::vector<std::string> words{"deltamesh"};
  std::string w;
  for (const char* p = args; *p; ++p) {
    if (*p == '\n') {
      words.push_back(w);
      w.clear();
    } else {
      w += *p;
    }
  }
  if (!w.empty()) words.push_back(w);
  std::vector<char*> argv;
  for (std::string& s : words) argv.push_back(s.data());
  argv.push_back(nullptr);
  const int code = deltamesh_cli_main(static_cast<int>(words.size()), argv.data());
  std::fflush(stdout);
  std::fflush(stderr);
  return code;
}

// Loads BASE.node, BASE.ele and (when present) BASE.poly; 0 on success, else
// 1 and dm_view_error() says why.
EMSCRIPTEN_KEEPALIVE int dm_view_load(const char* base) {
  view = View{};
  try {
    const std::string b = base;
    const deltamesh::Pslg nodes = deltamesh::read_node(b + ".node");
    const deltamesh::EleData ele = deltamesh::read_ele(b + ".ele", nodes.first_index);
    for (const deltamesh::Point& p : nodes.points) {
      view.xy.push_back(p.x);
      view.xy.push_back(p.y);
    }
    const std::size_t nt = ele.triangles.size() / 3;
    for (std::size_t t = 0; t < nt; ++t) {
      const auto a = ele.triangles[3 * t], bb = ele.triangles[3 * t + 1], c = ele.triangles[3 * t + 2];
      if (a >= nodes.points.size() || bb >= nodes.points.size() || c >= nodes.points.size())
        throw deltamesh::InputError("triangle " + std::to_string(t) + " names a vertex that is not in the .node file");
      view.triangles.insert(view.triangles.end(), {int(a), int(bb), int(c)});
      view.min_angle.push_back(
          deltamesh::smallest_angle_deg(nodes.points[a], nodes.points[bb], nodes.points[c]));
    }
    if (FILE* f = std::fopen((b + ".poly").c_str(), "r")) {
      std::fclose(f);
      const deltamesh::Pslg poly = deltamesh::read_poly(b + ".poly");
      for (const deltamesh::Segment& s : poly.segments) {
        view.segments.push_back(int(s.a));
        view.segments.push_back(int(s.b));
      }
    }
    return 0;
  } catch (const std::exception& e) {
    view.error = e.what();
    return 1;
  }
}

EMSCRIPTEN_KEEPALIVE const char* dm_view_error() { return view.error.c_str(); }
EMSCRIPTEN_KEEPALIVE int dm_view_vertices() { return int(view.xy.size() / 2); }
EMSCRIPTEN_KEEPALIVE const double* dm_view_xy() { return view.xy.data(); }
EMSCRIPTEN_KEEPALIVE int dm_view_triangles() { return int(view.min_angle.size()); }
EMSCRIPTEN_KEEPALIVE const int* dm_view_corners() { return view.triangles.data(); }
EMSCRIPTEN_KEEPALIVE const double* dm_view_min_angle() { return view.min_angle.data(); }
EMSCRIPTEN_KEEPALIVE int dm_view_segments() { return int(view.segments.size() / 2); }
EMSCRIPTEN_KEEPALIVE const int* dm_view_segment_ends() { return view.segments.data(); }

}  // extern "C"
