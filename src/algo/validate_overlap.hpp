// The validator's global overlap test (see validate_overlap.cpp for the
// argument). Internal to the validator.
#pragma once
#include <optional>
#include <string>

#include "deltamesh/mesh.hpp"
#include "deltamesh/validate.hpp"

namespace deltamesh::detail {

struct OverlapFinding {
  TriangleConflict conflict;
  std::string message;
};

// The first (leftmost) place where two real triangles' interiors intersect
// or two boundary edges meet other than at a common endpoint; nullopt when
// there is none. Needs what check() has verified before calling it: every
// real triangle strictly counter-clockwise, and every half-edge with a real
// twin paired with the reversed half-edge.
std::optional<OverlapFinding> find_overlap(const Mesh& mesh);

}  // namespace deltamesh::detail
