// The pipeline's steps shared between its files (internal).
#pragma once
#include <chrono>
#include <string>
#include <vector>

#include "deltamesh/pipeline.hpp"

namespace deltamesh::pipeline {

using Clock = std::chrono::steady_clock;

// Phase timings, in the order the command line's -V lists them.
struct Phases {
  std::vector<PhaseTime>& out;
  void add(std::string name, Clock::time_point since);
};

// The plan's refinement options with its progress callback.
RefineOptions refine_options(const Plan& plan);

// -r: the mesh rebuilt from the triangle list (6-node midpoints dropped),
// with -p its segments inserted and holes carved, with -c its boundary made
// of segments. Fills res.mesh, res.inserted, res.stats (domain, warnings,
// segment check with -C).
void rebuild_mesh(const Plan& plan, RunInput& in, RunResult& res, Phases& phases);

}  // namespace deltamesh::pipeline
