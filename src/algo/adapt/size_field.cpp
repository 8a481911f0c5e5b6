// Size fields: sizes at the vertices of a background mesh, interpolated.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "algo/adapt/background.hpp"
#include "deltamesh/adapt.hpp"
#include "deltamesh/errors.hpp"

namespace deltamesh {

namespace {

// Sizes at the vertices of a copy of a background mesh.
class BackgroundField {
 public:
  BackgroundField(const Mesh& bg, std::span<const double> sizes) : bg_(bg), sizes_(sizes.begin(), sizes.end()) {
    if (sizes_.size() != bg.num_vertices())
      throw InputError(std::to_string(sizes_.size()) + " sizes for a mesh of " + std::to_string(bg.num_vertices()) +
                       " vertices");
    for (std::size_t i = 0; i < sizes_.size(); ++i)
      if (!(sizes_[i] > 0) || !std::isfinite(sizes_[i]))
        throw InputError("the size of vertex " + std::to_string(i) + " is not a positive number", i);
  }

  double operator()(double x, double y) const {
    const adaptation::Weights w = bg_.weights({x, y});
    if (w.n == 0) return -1.0;
    double h = 0;
    for (int i = 0; i < w.n; ++i) h += w.w[i] * sizes_[w.v[i]];
    return h;
  }

 private:
  adaptation::BackgroundMesh bg_;
  std::vector<double> sizes_;
};

}  // namespace

SizeField size_field_from_vertices(const Mesh& background, std::span<const double> sizes) {
  auto field = std::make_shared<BackgroundField>(background, sizes);
  return [field](double x, double y) { return (*field)(x, y); };
}

}  // namespace deltamesh
