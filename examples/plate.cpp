// Meshes examples/plate.poly through the library: the same as
//   deltamesh -pA examples/plate.poly
// Build (after `make`): g++ -std=c++20 -O2 -Iinclude examples/plate.cpp build/libdeltamesh.a -o plate
#include <cstdio>

#include "deltamesh/deltamesh.hpp"
#include "deltamesh/triangulate.hpp"

int main(int argc, char** argv) {
  namespace dm = deltamesh;
  try {
    const dm::Pslg pslg = dm::read_poly(argc > 1 ? argv[1] : "examples/plate.poly");
    dm::TriangulateOptions opt;
    opt.domain.regional_attributes = true;  // -A: attribute per triangle from the region points
    dm::TriangulateStats stats;
    const dm::Mesh mesh = dm::triangulate(pslg, opt, &stats);

    dm::CheckOptions check;
    check.convex_hull = false;  // a plate with holes is not convex
    const dm::CheckReport report = dm::check(mesh, check);
    std::printf("%zu triangles, %zu vertices; %s\n", mesh.num_triangles(), mesh.num_vertices(),
                report.summary().c_str());
    for (dm::TriId t = 0; t < 3 && t < mesh.num_triangles(); ++t) {
      const auto v = mesh.triangle(t);
      std::printf("triangle %u: vertices %u %u %u, region attribute %g\n", t, v[0], v[1], v[2],
                  mesh.triangle_attributes()[t]);
    }
    dm::write_node(mesh, "plate.1.node");
    dm::write_ele(mesh, "plate.1.ele");
    return report.ok() ? 0 : 1;
  } catch (const dm::Error& e) {  // ParseError (file:line), InputError, IoError
    std::fprintf(stderr, "plate: %s\n", e.what());
    return 2;
  }
}
