// libFuzzer target: the .ele reader. The first byte chooses the numbering of
// the vertices (0 or 1, as the .node file's); the rest is the file.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "deltamesh/triangle_io.hpp"
#include "fuzz_util.hpp"

namespace fz = deltamesh::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int first_index = data[0] & 1;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::string path = fz::temp_dir().write("in.ele", text);
  try {
    const deltamesh::EleData d = deltamesh::read_ele(path, first_index);
    DELTAMESH_FUZZ_CHECK(d.triangles.size() % 3 == 0, "3 vertices per triangle");
    const std::size_t nt = d.triangles.size() / 3;
    DELTAMESH_FUZZ_CHECK(d.attributes.size() == nt * d.num_attributes, "attributes per triangle");
    for (std::size_t t = 0; t < nt; ++t) {
      const auto a = d.triangles[3 * t], b = d.triangles[3 * t + 1], c = d.triangles[3 * t + 2];
      DELTAMESH_FUZZ_CHECK(a != b && b != c && a != c, "a triangle uses a vertex twice");
      DELTAMESH_FUZZ_CHECK(a < deltamesh::kInfinite && b < deltamesh::kInfinite && c < deltamesh::kInfinite,
                           "a vertex id that is not a vertex");
    }
    for (const double a : d.attributes) DELTAMESH_FUZZ_CHECK(std::isfinite(a), "attribute not finite");
  } catch (const deltamesh::ParseError& e) {
    fz::check_parse_error(e, path, text);
  } catch (...) {
    fz::unexpected_exception("read_ele");
  }
  return 0;
}
