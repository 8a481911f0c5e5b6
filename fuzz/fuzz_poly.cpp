// libFuzzer target: the .poly reader. The input is split at the first line
// "---": what comes before is FILE.poly, what comes after (if anything) is
// FILE.node, which read_poly reads when the .poly lists no vertices.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "deltamesh/triangle_io.hpp"
#include "fuzz_util.hpp"
#include "pslg_checks.hpp"

namespace fz = deltamesh::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  std::string_view poly = all, node;
  const std::size_t cut = all.find("\n---\n");
  if (cut != std::string_view::npos) {
    poly = all.substr(0, cut + 1);
    node = all.substr(cut + 5);
  }
  fz::TempDir& dir = fz::temp_dir();
  const std::string path = dir.write("in.poly", poly);
  std::string node_path;
  if (cut != std::string_view::npos)
    node_path = dir.write("in.node", node);
  else
    dir.remove("in.node");
  try {
    const deltamesh::Pslg g = deltamesh::read_poly(path);
    fz::check_pslg(g);
  } catch (const deltamesh::ParseError& e) {
    if (!node_path.empty() && e.file() == node_path)
      fz::check_parse_error(e, node_path, node);
    else
      fz::check_parse_error(e, path, poly);
  } catch (...) {
    fz::unexpected_exception("read_poly");
  }
  return 0;
}
