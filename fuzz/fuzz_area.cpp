// libFuzzer target: the .area reader.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "deltamesh/triangle_io.hpp"
#include "fuzz_util.hpp"

namespace fz = deltamesh::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string path = fz::temp_dir().write("in.area", text);
  try {
    const std::vector<double> areas = deltamesh::read_area(path);
    for (const double a : areas)
      DELTAMESH_FUZZ_CHECK(a == -1.0 || (a > 0 && std::isfinite(a)), "area bound " + std::to_string(a));
  } catch (const deltamesh::ParseError& e) {
    fz::check_parse_error(e, path, text);
  } catch (...) {
    fz::unexpected_exception("read_area");
  }
  return 0;
}
