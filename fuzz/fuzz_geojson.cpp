// libFuzzer target: the GeoJSON reader (parse_geojson, in memory). The first
// byte chooses which property options are set; the rest is the text.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "deltamesh/formats.hpp"
#include "fuzz_util.hpp"
#include "pslg_checks.hpp"

namespace fz = deltamesh::fuzz;

namespace {

// Line and column of the byte just past `text` (1-based), as a bound for
// the position an error may name.
std::size_t lines_of(std::string_view text) { return fz::line_count(text) + 1; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  deltamesh::GeoJsonReadOptions opt;
  if (flags & 1) opt.attribute_property = "a";
  if (flags & 2) opt.area_property = "area";
  if (flags & 4) opt.marker_property = "m";
  if (flags & 8) opt.outer_marker = -7, opt.hole_marker = 1 << 30;
  deltamesh::GeoJsonInfo info;
  try {
    const deltamesh::Pslg g = deltamesh::parse_geojson(text, "fuzz.geojson", opt, &info);
    fz::check_pslg(g, false);
    DELTAMESH_FUZZ_CHECK(info.holes <= info.rings, "more holes than rings");
    DELTAMESH_FUZZ_CHECK(info.seeds == g.regions.size(), "one region per seed");
    DELTAMESH_FUZZ_CHECK(g.holes.empty(), "GeoJSON holes are rings, not hole points");
  } catch (const deltamesh::JsonParseError& e) {
    DELTAMESH_FUZZ_CHECK(e.file() == "fuzz.geojson", e.what());
    DELTAMESH_FUZZ_CHECK(e.line() >= 1 && e.line() <= lines_of(text), e.what());
    DELTAMESH_FUZZ_CHECK(e.column() >= 1 && e.column() <= text.size() + 1, e.what());
  } catch (const deltamesh::ParseError& e) {
    DELTAMESH_FUZZ_CHECK(e.file() == "fuzz.geojson", e.what());
  } catch (...) {
    fz::unexpected_exception("parse_geojson");
  }
  return 0;
}
