// Fast line/token reader for the plain-text input formats.
//
// A regular file is mapped into memory (no copy, no zero-filled buffer);
// anything else (pipes, files the kernel reports as empty) is read whole.
// Lines are split in place into whitespace-separated tokens (string_views
// into the text).
// `#` starts a comment anywhere on a line; blank and comment-only lines are
// skipped; CRLF line ends and a missing final newline are fine. Numbers are
// parsed by parse_decimal_prefix below when it can, else std::from_chars,
// never with iostreams; both give the same bits. Every problem is
// reported as ParseError(file, line, problem) naming the 1-based line.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "deltamesh/errors.hpp"
#include "deltamesh/geometry.hpp"

namespace deltamesh::io {

// The whole content of a file. Throws IoError when it cannot be opened or read.
std::string read_whole_file(const std::string& path);

enum class NumberStatus : std::uint8_t { Ok, NotANumber, NotAnInteger, OutOfRange };

// The common spellings of a decimal number, fast: [-]digits[.digits][e[+-]digits]
// with at most 19 significant digits and a result that is exactly the
// correctly rounded double (Clinger's fast path, or a division in 64-bit
// extended precision that is checked not to land on a rounding tie). Returns
// the end of the number, or nullptr when the spelling or value is outside
// that path: the caller then uses std::from_chars, which gives the same
// value, so this never changes what a file means.
const char* parse_decimal_prefix(const char* first, const char* last, double& value);

// Parses the whole token as a double (a leading '+' is accepted, as strtod
// does). NaN and infinities parse as such: finiteness is the caller's check.
NumberStatus parse_double(std::string_view token, double& value);
// Parses the whole token as an integer. A token written as an integral
// floating-point value ("3.0", "1e2") is accepted too.
NumberStatus parse_integer(std::string_view token, long long& value);

class TextReader {
 public:
  TextReader(std::string file_name, std::string text);
  // Maps `path` (a regular file) or reads it whole. Throws IoError as
  // read_whole_file does.
  static TextReader open(const std::string& path);
  ~TextReader();
  // The tokens point into the text: neither copied nor moved.
  TextReader(const TextReader&) = delete;
  TextReader& operator=(const TextReader&) = delete;

  const std::string& file() const { return file_; }

  // Moves to the next line that holds data; false at the end of the file.
  bool next_line();
  // True when a line with data remains after the current one (skips blank
  // and comment-only lines but does not consume the data line).
  bool has_more_data();
  // 1-based number of the current line (0 before the first next_line()).
  std::size_t line() const { return line_; }
  // Number of the last line of the file (for end-of-file messages).
  std::size_t last_line() const;

  // Fast path for the common entry line "<id> <x> <y> [<marker>]": parses
  // the next line in place when it is exactly that shape, with id ==
  // expected_id, finite coordinates and a marker that fits in an int, and
  // moves past it. Returns false,
  // consuming nothing, for anything else (comments, blank lines, extra
  // fields, odd spellings, errors): the caller then takes the general path,
  // which gives the precise error message.
  bool try_point_line(long long expected_id, bool with_marker, double& x, double& y, long long& marker);

  // try_point_line for the next `count` lines at once (ids first_id,
  // first_id + 1, ...), on up to `threads` threads: the rest of the file is
  // cut at line starts into pieces parsed concurrently, then joined in
  // order. All or nothing: false, consuming nothing, when any of those lines
  // is not of that shape (a comment, a blank line, an error...), so the
  // caller's general path reads them and words any error as before; true
  // when all were, with `points` and `markers` appended (the first piece is
  // parsed straight into them: reserve their capacity beforehand).
  bool try_point_lines(long long first_id, std::size_t count, bool with_marker, unsigned threads,
                       std::vector<Point>& points, std::vector<int>& markers);

  std::size_t size() const { return tokens_.size(); }
  std::string_view token(std::size_t i) const { return tokens_[i]; }

  // Bytes not yet consumed, and the number of data lines among them. The
  // first is O(1), the second scans the rest of the file (for error paths).
  std::size_t bytes_left() const { return text_.size() - pos_; }
  std::size_t count_data_lines_left() const;

  [[noreturn]] void fail(const std::string& problem) const { fail_at(line_, problem); }
  [[noreturn]] void fail_at(std::size_t line, const std::string& problem) const {
    throw ParseError(file_, line, problem);
  }

  // Token i of the current line as a number. `describe()` returns what the
  // token should be ("the x coordinate of vertex 5") and is only called to
  // build an error message.
  template <class Describe>
  double number(std::size_t i, Describe&& describe) const {
    double v;
    const NumberStatus s = parse_double(tokens_[i], v);
    if (s != NumberStatus::Ok) number_error(i, s, describe());
    return v;
  }
  // Like number() but also rejects NaN and infinities.
  template <class Describe>
  double finite_number(std::size_t i, Describe&& describe) const {
    const double v = number(i, describe);
    if (!(v - v == 0.0)) not_finite_error(i, describe());
    return v;
  }
  template <class Describe>
  long long integer(std::size_t i, Describe&& describe) const {
    long long v;
    const NumberStatus s = parse_integer(tokens_[i], v);
    if (s != NumberStatus::Ok) number_error(i, s, describe());
    return v;
  }

 private:
  [[noreturn]] void number_error(std::size_t i, NumberStatus s, const std::string& what) const;
  [[noreturn]] void not_finite_error(std::size_t i, const std::string& what) const;
  // End of the line starting at `from` (index of '\n' or text_.size()).
  std::size_t line_end(std::size_t from) const;
  // Whether [from, end) holds a token before any comment.
  bool holds_data(std::size_t from, std::size_t end) const;

  struct Mapping {
    void* address = nullptr;
    std::size_t length = 0;
  };
  TextReader(std::string file_name, Mapping mapping);

  std::string file_;
  std::string owned_;  // the text when it was read, not mapped
  Mapping mapping_;    // the text when it was mapped
  std::string_view text_;
  std::size_t pos_ = 0;        // start of the first unconsumed line
  std::size_t next_line_ = 1;  // its 1-based number
  std::size_t line_ = 0;
  std::vector<std::string_view> tokens_;
};

// "1 vertex" / "3 vertices".
std::string plural(long long n, std::string_view one, std::string_view many);

}  // namespace deltamesh::io
