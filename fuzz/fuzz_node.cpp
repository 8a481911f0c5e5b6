// libFuzzer target: the .node reader. Any input must give a Pslg that
// satisfies the reader's promises or a ParseError naming the file and one of
// its lines; never a crash, a sanitizer report, a hang or a huge allocation.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "deltamesh/triangle_io.hpp"
#include "fuzz_util.hpp"
#include "pslg_checks.hpp"

namespace fz = deltamesh::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::string path = fz::temp_dir().write("in.node", text);
  try {
    const deltamesh::Pslg g = deltamesh::read_node(path);
    fz::check_pslg(g);
    DELTAMESH_FUZZ_CHECK(g.segments.empty() && g.holes.empty() && g.regions.empty(), "a .node has only vertices");
  } catch (const deltamesh::ParseError& e) {
    fz::check_parse_error(e, path, text);
  } catch (...) {
    fz::unexpected_exception("read_node");
  }
  return 0;
}
