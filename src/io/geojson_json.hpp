// A small JSON (RFC 8259) parser for the GeoJSON reader: the whole text is
// parsed into a compact tree (one vector of nodes; arrays of numbers only,
// such as GeoJSON positions, are stored as one node over a pool of doubles).
// Every node keeps its byte offset, so errors found later (while reading the
// GeoJSON structure) name the line and column too.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "deltamesh/formats.hpp"

namespace deltamesh::io {

class Json {
 public:
  enum class Kind : std::uint8_t { Null, False, True, Number, String, Array, Object, NumberArray };
  using Id = std::uint32_t;
  static constexpr Id kNoNode = static_cast<Id>(-1);

  // Parses `text`; throws JsonParseError naming `file`, line and column.
  Json(std::string_view text, std::string file);

  Id root() const { return 0; }
  Kind kind(Id n) const { return nodes_[n].kind; }
  std::size_t offset(Id n) const { return nodes_[n].offset; }
  double number(Id n) const { return nodes_[n].number; }
  std::string_view string(Id n) const { return span(nodes_[n].range.begin, nodes_[n].range.end); }
  // Elements of an Array (not of a NumberArray).
  std::size_t size(Id n) const { return nodes_[n].range.end - nodes_[n].range.begin; }
  Id item(Id n, std::size_t i) const { return items_[nodes_[n].range.begin + i]; }
  // Values of a NumberArray.
  const double* numbers(Id n) const { return numbers_.data() + nodes_[n].range.begin; }
  std::size_t count(Id n) const { return size(n); }
  bool is_array(Id n) const { return kind(n) == Kind::Array || kind(n) == Kind::NumberArray; }
  // The value of member `key` of an Object (the last one when repeated), or kNoNode.
  Id member(Id object, std::string_view key) const;

  // What a node is, for messages: "a string", "an array", ...
  static const char* describe(Kind k);

  [[noreturn]] void fail_at(std::size_t offset, const std::string& problem) const;
  [[noreturn]] void fail(Id n, const std::string& problem) const { fail_at(offset(n), problem); }
  const std::string& file() const { return file_; }

 private:
  // 16 bytes: files are limited to 4 GiB, so offsets fit 32 bits.
  struct Range {
    std::uint32_t begin, end;  // items_ / members_ / numbers_ / chars_ range
  };
  struct Node {
    Kind kind = Kind::Null;
    std::uint32_t offset = 0;
    union {
      Range range;
      double number;
    };
    Node() : range{0, 0} {}
  };
  struct Member {
    Range key;  // in chars_
    Id value;
  };
  class Parser;

  std::string_view span(std::uint32_t begin, std::uint32_t end) const {
    return std::string_view(chars_).substr(begin, end - begin);
  }

  std::string_view text_;
  std::string file_;
  std::vector<Node> nodes_;
  std::vector<Id> items_;
  std::vector<Member> members_;
  std::string chars_;  // every decoded string and member name, end to end
  std::vector<double> numbers_;
};

}  // namespace deltamesh::io
