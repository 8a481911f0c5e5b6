// Planar straight-line graph: the input of every meshing call.
#pragma once
#include <cstddef>
#include <vector>

#include "deltamesh/geometry.hpp"

namespace deltamesh {

struct Segment {
  VertexId a = 0;
  VertexId b = 0;
  int marker = 0;
};

// A regional attribute / area constraint seed (a .poly region line).
struct RegionSeed {
  Point p;
  double attribute = 0.0;
  double max_area = -1.0;  // negative: no bound
};

struct Pslg {
  std::vector<Point> points;
  std::vector<int> point_markers;          // empty, or one per point
  std::size_t num_point_attributes = 0;
  std::vector<double> point_attributes;    // num_point_attributes per point
  std::vector<Segment> segments;
  std::vector<Point> holes;
  std::vector<RegionSeed> regions;
  int first_index = 0;                     // 0 or 1: the numbering the file used
};

}  // namespace deltamesh
