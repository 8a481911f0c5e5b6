#include "io/geojson_json.hpp"

#include <charconv>

#include <cstdio>
#include <cmath>
#include <system_error>

#include "core/float_chars.hpp"

namespace deltamesh {

JsonParseError::JsonParseError(std::string file, std::size_t line, std::size_t column, const std::string& problem)
    : ParseError(file, line, problem),
      column_(column),
      message_(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + problem) {}

namespace io {

namespace {

constexpr int kMaxDepth = 256;

std::string shown(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7f) return std::string("'") + c + "'";
  if (c == '\n') return "a line break";
  char buf[16];
  std::snprintf(buf, sizeof buf, "byte 0x%02x", u);
  return buf;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xc0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xe0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  } else {
    out += static_cast<char>(0xf0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  }
}

}  // namespace

class Json::Parser {
 public:
  explicit Parser(Json& j) : j_(j), s_(j.text_), n_(s_.size()) {}

  void run() {
    // A UTF-8 byte order mark is tolerated.
    if (n_ >= 3 && s_.substr(0, 3) == "\xEF\xBB\xBF") p_ = 3;
    skip_ws();
    if (p_ >= n_) j_.fail_at(p_, "the file is empty (expected a JSON value)");
    value(0);
    skip_ws();
    if (p_ < n_) j_.fail_at(p_, "unexpected " + shown(s_[p_]) + " after the end of the JSON value");
  }

 private:
  void skip_ws() {
    while (p_ < n_) {
      const char c = s_[p_];
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') return;
      ++p_;
    }
  }

  Id new_node(Kind k) {
    if (j_.nodes_.size() >= static_cast<std::size_t>(kNoNode) - 1) j_.fail_at(p_, "too many JSON values");
    Node node;
    node.kind = k;
    node.offset = static_cast<std::uint32_t>(p_);
    j_.nodes_.push_back(node);
    return static_cast<Id>(j_.nodes_.size() - 1);
  }

  [[noreturn]] void unexpected(const char* expected) {
    if (p_ >= n_) j_.fail_at(p_, std::string("unexpected end of file: expected ") + expected);
    j_.fail_at(p_, "expected " + std::string(expected) + ", found " + shown(s_[p_]));
  }

  void literal(std::string_view word, Kind k) {
    if (s_.substr(p_, word.size()) != word) unexpected("a JSON value");
    new_node(k);
    p_ += word.size();
  }

  Id value(int depth) {
    if (p_ >= n_) unexpected("a JSON value");
    const char c = s_[p_];
    switch (c) {
      case '{': return object(depth);
      case '[': return array(depth);
      case '"': {
        const Id id = new_node(Kind::String);
        j_.nodes_[id].range = string_token();
        return id;
      }
      case 't': literal("true", Kind::True); return static_cast<Id>(j_.nodes_.size() - 1);
      case 'f': literal("false", Kind::False); return static_cast<Id>(j_.nodes_.size() - 1);
      case 'n': literal("null", Kind::Null); return static_cast<Id>(j_.nodes_.size() - 1);
      default:
        if (c == '-' || (c >= '0' && c <= '9')) {
          const Id id = new_node(Kind::Number);
          j_.nodes_[id].number = number_token();
          return id;
        }
        if (s_.substr(p_, 3) == "NaN" || s_.substr(p_, 8) == "Infinity")
          j_.fail_at(p_, "NaN and Infinity are not JSON numbers");
        unexpected("a JSON value");
    }
  }

  double number_token() {
    const std::size_t start = p_;
    if (s_[p_] == '-') ++p_;
    if (p_ < n_ && s_[p_] == '0') {
      ++p_;
    } else if (p_ < n_ && s_[p_] >= '1' && s_[p_] <= '9') {
      while (p_ < n_ && s_[p_] >= '0' && s_[p_] <= '9') ++p_;
    } else {
      unexpected("a digit");
    }
    if (p_ < n_ && s_[p_] == '.') {
      ++p_;
      if (!(p_ < n_ && s_[p_] >= '0' && s_[p_] <= '9')) unexpected("a digit after the decimal point");
      while (p_ < n_ && s_[p_] >= '0' && s_[p_] <= '9') ++p_;
    }
    if (p_ < n_ && (s_[p_] == 'e' || s_[p_] == 'E')) {
      ++p_;
      if (p_ < n_ && (s_[p_] == '+' || s_[p_] == '-')) ++p_;
      if (!(p_ < n_ && s_[p_] >= '0' && s_[p_] <= '9')) unexpected("a digit in the exponent");
      while (p_ < n_ && s_[p_] >= '0' && s_[p_] <= '9') ++p_;
    }
    double v = 0.0;
    const auto r = chars::parse_double(s_.data() + start, s_.data() + p_, v);
    if (r.ec == std::errc::result_out_of_range) {
      // Underflow to zero is harmless; overflow is not a usable coordinate.
      bool tiny = false;
      for (std::size_t i = start; i < p_; ++i)
        if (s_[i] == 'e' || s_[i] == 'E') tiny = s_[i + 1] == '-';
      if (!tiny) j_.fail_at(start, "number " + std::string(s_.substr(start, p_ - start)) + " is out of range");
      v = 0.0;
    } else if (r.ec != std::errc() || r.ptr != s_.data() + p_) {
      j_.fail_at(start, "malformed number");
    }
    return v;
  }

  unsigned hex4() {
    if (p_ + 4 > n_) unexpected("four hex digits after \\u");
    unsigned v = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = s_[p_];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= unsigned(c - '0');
      else if (c >= 'a' && c <= 'f') v |= unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= unsigned(c - 'A' + 10);
      else unexpected("a hex digit in a \\u escape");
      ++p_;
    }
    return v;
  }

  // Decodes a string into chars_; returns its range there.
  Range string_token() {
    const std::size_t start = p_;
    ++p_;  // opening quote
    std::string& out = j_.chars_;
    const auto begin = static_cast<std::uint32_t>(out.size());
    while (true) {
      // Plain characters up to the next quote, backslash or control character in one go.
      std::size_t q = p_;
      while (q < n_ && s_[q] != '"' && s_[q] != '\\' && static_cast<unsigned char>(s_[q]) >= 0x20) ++q;
      out.append(s_.data() + p_, q - p_);
      p_ = q;
      if (p_ >= n_) j_.fail_at(start, "unterminated string (no closing '\"' before the end of the file)");
      const char c = s_[p_];
      if (c == '"') {
        ++p_;
        if (out.size() >= static_cast<std::size_t>(kNoNode)) j_.fail_at(start, "too much text in strings");
        return Range{begin, static_cast<std::uint32_t>(out.size())};
      }
      if (static_cast<unsigned char>(c) < 0x20) {
        if (c == '\n') j_.fail_at(start, "unterminated string (a line break before the closing '\"')");
        j_.fail_at(p_, "control character " + shown(c) + " in a string (escape it)");
      }
      ++p_;
      if (p_ >= n_) unexpected("an escape character after '\\'");
      const char e = s_[p_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xd800 && cp < 0xdc00 && p_ + 1 < n_ && s_[p_] == '\\' && s_[p_ + 1] == 'u') {
            const std::size_t save = p_;
            p_ += 2;
            const unsigned low = hex4();
            if (low >= 0xdc00 && low < 0xe000) {
              cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
            } else {
              p_ = save;
            }
          }
          if (cp >= 0xd800 && cp < 0xe000) cp = 0xfffd;  // lone surrogate
          append_utf8(out, cp);
          break;
        }
        default:
          --p_;
          j_.fail_at(p_ - 1, "invalid escape '\\" + std::string(1, e) + "' in a string");
      }
    }
  }

  Id array(int depth) {
    if (depth >= kMaxDepth) j_.fail_at(p_, "arrays and objects nested more than " + std::to_string(kMaxDepth) + " deep");
    const Id id = new_node(Kind::Array);
    ++p_;
    const std::size_t mark = stack_.size();
    bool all_numbers = true;
    skip_ws();
    if (p_ < n_ && s_[p_] == ']') {
      ++p_;
    } else {
      while (true) {
        skip_ws();
        const Id child = value(depth + 1);
        all_numbers = all_numbers && j_.nodes_[child].kind == Kind::Number;
        stack_.push_back(child);
        skip_ws();
        if (p_ < n_ && s_[p_] == ',') {
          ++p_;
          skip_ws();
          if (p_ < n_ && s_[p_] == ']') j_.fail_at(p_, "trailing ',' before ']' (not allowed in JSON)");
          continue;
        }
        if (p_ < n_ && s_[p_] == ']') {
          ++p_;
          break;
        }
        unexpected("',' or ']' after an array element");
      }
    }
    const std::size_t count = stack_.size() - mark;
    Node& node = j_.nodes_[id];
    if (all_numbers && count > 0) {
      // The children are the last `count` nodes: fold them into the pool.
      node.kind = Kind::NumberArray;
      const auto begin = static_cast<std::uint32_t>(j_.numbers_.size());
      for (std::size_t i = mark; i < stack_.size(); ++i) j_.numbers_.push_back(j_.nodes_[stack_[i]].number);
      node.range = Range{begin, static_cast<std::uint32_t>(j_.numbers_.size())};
      j_.nodes_.resize(id + 1);
    } else {
      const auto begin = static_cast<std::uint32_t>(j_.items_.size());
      j_.items_.insert(j_.items_.end(), stack_.begin() + static_cast<std::ptrdiff_t>(mark), stack_.end());
      node.range = Range{begin, static_cast<std::uint32_t>(j_.items_.size())};
    }
    stack_.resize(mark);
    return id;
  }

  Id object(int depth) {
    if (depth >= kMaxDepth) j_.fail_at(p_, "arrays and objects nested more than " + std::to_string(kMaxDepth) + " deep");
    const Id id = new_node(Kind::Object);
    ++p_;
    const std::size_t mark = pairs_.size();
    skip_ws();
    if (p_ < n_ && s_[p_] == '}') {
      ++p_;
    } else {
      while (true) {
        skip_ws();
        if (p_ >= n_ || s_[p_] != '"') unexpected("a member name in double quotes");
        const Range key = string_token();
        skip_ws();
        if (p_ >= n_ || s_[p_] != ':') unexpected("':' after a member name");
        ++p_;
        skip_ws();
        const Id child = value(depth + 1);
        pairs_.push_back(Member{key, child});
        skip_ws();
        if (p_ < n_ && s_[p_] == ',') {
          ++p_;
          skip_ws();
          if (p_ < n_ && s_[p_] == '}') j_.fail_at(p_, "trailing ',' before '}' (not allowed in JSON)");
          continue;
        }
        if (p_ < n_ && s_[p_] == '}') {
          ++p_;
          break;
        }
        unexpected("',' or '}' after an object member");
      }
    }
    Node& node = j_.nodes_[id];
    const auto begin = static_cast<std::uint32_t>(j_.members_.size());
    j_.members_.insert(j_.members_.end(), pairs_.begin() + static_cast<std::ptrdiff_t>(mark), pairs_.end());
    node.range = Range{begin, static_cast<std::uint32_t>(j_.members_.size())};
    pairs_.resize(mark);
    return id;
  }

  Json& j_;
  std::string_view s_;
  std::size_t n_;
  std::size_t p_ = 0;
  std::vector<Id> stack_;
  std::vector<Member> pairs_;
};

Json::Json(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {
  if (text.size() >= static_cast<std::size_t>(kNoNode)) fail_at(0, "file too large (4 GiB or more)");
  Parser(*this).run();
}

Json::Id Json::member(Id object, std::string_view key) const {
  const Range r = nodes_[object].range;
  for (std::uint32_t i = r.end; i > r.begin; --i)
    if (span(members_[i - 1].key.begin, members_[i - 1].key.end) == key) return members_[i - 1].value;
  return kNoNode;
}

const char* Json::describe(Kind k) {
  switch (k) {
    case Kind::Null: return "null";
    case Kind::False:
    case Kind::True: return "a boolean";
    case Kind::Number: return "a number";
    case Kind::String: return "a string";
    case Kind::Array:
    case Kind::NumberArray: return "an array";
    case Kind::Object: return "an object";
  }
  return "a value";
}

void Json::fail_at(std::size_t offset, const std::string& problem) const {
  if (offset > text_.size()) offset = text_.size();
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < offset; ++i)
    if (text_[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
  // Columns count characters: UTF-8 continuation bytes do not start one.
  std::size_t column = 1;
  for (std::size_t i = line_start; i < offset; ++i)
    if ((static_cast<unsigned char>(text_[i]) & 0xc0) != 0x80) ++column;
  throw JsonParseError(file_, line, column, problem);
}

}  // namespace io
}  // namespace deltamesh
