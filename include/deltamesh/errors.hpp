// Typed errors. Bad input is an exception carrying data; failing to reach a
// quality target is a result, not an exception.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>

namespace deltamesh {

// Base of every error the library throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Malformed input file: names the file, the 1-based line and what was expected.
class ParseError : public Error {
 public:
  ParseError(std::string file, std::size_t line, const std::string& problem)
      : Error(file + ":" + std::to_string(line) + ": " + problem),
        file_(std::move(file)), line_(line), problem_(problem) {}
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_;
  std::size_t line_;
  std::string problem_;
};

// Input that parses but cannot be meshed (NaN, overflow-prone magnitude,
// all points collinear, ...). `index` names the offending vertex when known.
class InputError : public Error {
 public:
  explicit InputError(const std::string& what, std::size_t index = static_cast<std::size_t>(-1))
      : Error(what), index_(index) {}
  std::size_t index() const { return index_; }

 private:
  std::size_t index_;
};

// Input that cannot be meshed because of one vertex (a coordinate out of
// range, a size that is not positive): `index` is its 0-based position in
// the input's vertex list, `problem` what is wrong without naming it, so a
// front end can name the vertex as the user's file numbers it.
class VertexError : public InputError {
 public:
  VertexError(const std::string& what, std::size_t index, std::string problem)
      : InputError(what, index), problem_(std::move(problem)) {}
  const std::string& problem() const { return problem_; }

 private:
  std::string problem_;
};

// An output file could not be written.
class IoError : public Error {
 public:
  using Error::Error;
};

// A broken invariant: a bug in deltamesh, never the input's fault. The CLI
// exits 70 on it, Python raises deltamesh.InternalError, fuzz targets treat it
// as a crash. `where` names the function that found it.
class InternalError : public Error {
 public:
  InternalError(const std::string& where, const std::string& what)
      : Error(where + ": " + what), where_(where) {}
  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace deltamesh

namespace deltamesh {

// Two input segments cross (reported under --strict instead of being split).
class IntersectingSegments : public InputError {
 public:
  IntersectingSegments(std::size_t first, std::size_t second)
      : InputError("segments " + std::to_string(first) + " and " + std::to_string(second) + " cross"),
        first_(first), second_(second) {}
  std::size_t first() const { return first_; }
  std::size_t second() const { return second_; }

 private:
  std::size_t first_, second_;
};

// Two triangles of a mesh given as a triangle list (-r, mesh_from_triangles)
// overlap or meet other than edge to edge. first() < second() are indices
// into that list (0-based); the text says how they meet.
class OverlappingTriangles : public InputError {
 public:
  OverlappingTriangles(std::size_t first, std::size_t second, const std::string& how)
      : InputError("triangles " + std::to_string(first) + " and " + std::to_string(second) + " " + how, first),
        first_(first), second_(second), how_(how) {}
  std::size_t first() const { return first_; }
  std::size_t second() const { return second_; }
  const std::string& how() const { return how_; }

 private:
  std::size_t first_, second_;
  std::string how_;
};

// A segment that cannot go into an existing mesh (insert_segments, -r with
// -p): an endpoint out of range or in no triangle, a way outside the mesh,
// or (strict) a crossing with a segment already there. `segment()` is its
// index in the list given; `problem()` says what is wrong without naming it.
class SegmentError : public InputError {
 public:
  SegmentError(std::size_t segment, std::size_t a, std::size_t b, const std::string& problem)
      : InputError("segment " + std::to_string(segment) + " (vertices " + std::to_string(a) + "-" +
                       std::to_string(b) + ") " + problem,
                   segment),
        segment_(segment), a_(a), b_(b), problem_(problem) {}
  std::size_t segment() const { return segment_; }
  std::size_t a() const { return a_; }
  std::size_t b() const { return b_; }
  const std::string& problem() const { return problem_; }

 private:
  std::size_t segment_, a_, b_;
  std::string problem_;
};

}  // namespace deltamesh
