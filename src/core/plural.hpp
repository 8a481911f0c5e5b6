// "1 triangle", "2 triangles": counts in messages and summaries.
#pragma once
#include <cstddef>
#include <string>

namespace deltamesh {

inline std::string count_of(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace deltamesh
