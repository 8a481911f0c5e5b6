#include "io/text_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <system_error>

namespace deltamesh::io {

namespace {

std::string errno_text(int err) { return std::generic_category().message(err); }

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::string read_whole_file(const std::string& path) {
  Fd fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
  if (fd.get() < 0) throw IoError("cannot open '" + path + "': " + errno_text(errno));
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) throw IoError("cannot read '" + path + "': " + errno_text(errno));
  if (S_ISDIR(st.st_mode)) throw IoError("cannot read '" + path + "': " + errno_text(EISDIR));
  std::string text;
  // Regular files: one read of the known size. Pipes and growing files: the
  // buffer grows until end of file.
  std::size_t capacity = S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : 65536;
  text.resize(capacity);
  std::size_t used = 0;
  for (;;) {
    if (used == text.size()) text.resize(text.size() * 2);
    const ssize_t got = ::read(fd.get(), text.data() + used, text.size() - used);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw IoError("cannot read '" + path + "': " + errno_text(errno));
    }
    if (got == 0) break;
    used += static_cast<std::size_t>(got);
  }
  text.resize(used);
  return text;
}

NumberStatus parse_double(std::string_view token, double& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  const bool plus = first != last && *first == '+';
  if (plus) ++first;
  if (first == last || (plus && (*first == '+' || *first == '-'))) return NumberStatus::NotANumber;
  const auto [ptr, ec] = std::from_chars(first, last, value, std::chars_format::general);
  if (ptr != last) return NumberStatus::NotANumber;
  if (ec == std::errc::result_out_of_range) return NumberStatus::OutOfRange;
  if (ec != std::errc()) return NumberStatus::NotANumber;
  return NumberStatus::Ok;
}

NumberStatus parse_integer(std::string_view token, long long& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  const bool plus = first != last && *first == '+';
  if (plus) ++first;
  if (first == last || (plus && (*first == '+' || *first == '-'))) return NumberStatus::NotANumber;
  const auto [ptr, ec] = std::from_chars(first, last, value, 10);
  if (ptr == last) return ec == std::errc::result_out_of_range ? NumberStatus::OutOfRange : NumberStatus::Ok;
  // Not a plain integer: accept an integral floating-point spelling ("3.0").
  double d;
  const NumberStatus s = parse_double(token, d);
  if (s != NumberStatus::Ok) return s;
  if (!std::isfinite(d) || d != std::floor(d)) return NumberStatus::NotAnInteger;
  if (std::fabs(d) >= 9.2e18) return NumberStatus::OutOfRange;
  value = static_cast<long long>(d);
  return NumberStatus::Ok;
}

std::string plural(long long n, std::string_view one, std::string_view many) {
  std::string s = std::to_string(n);
  s += ' ';
  s += n == 1 ? one : many;
  return s;
}

TextReader::TextReader(std::string file_name, std::string text)
    : file_(std::move(file_name)), text_(std::move(text)) {
  tokens_.reserve(16);
  // A UTF-8 byte order mark (some Windows editors write one) is not data.
  if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
}

TextReader TextReader::open(const std::string& path) { return TextReader(path, read_whole_file(path)); }

std::size_t TextReader::line_end(std::size_t from) const {
  const void* nl = std::memchr(text_.data() + from, '\n', text_.size() - from);
  return nl == nullptr ? text_.size() : static_cast<std::size_t>(static_cast<const char*>(nl) - text_.data());
}

bool TextReader::holds_data(std::size_t from, std::size_t end) const {
  for (std::size_t i = from; i < end; ++i) {
    const char c = text_[i];
    if (c == '#') return false;
    if (!is_space(c)) return true;
  }
  return false;
}

bool TextReader::has_more_data() {
  while (pos_ < text_.size()) {
    const std::size_t end = line_end(pos_);
    if (holds_data(pos_, end)) return true;
    pos_ = end + 1;  // may step one past the end: clamped below
    ++next_line_;
  }
  pos_ = text_.size();
  return false;
}

bool TextReader::next_line() {
  // One pass over the line: skip blank and comment-only lines, then split
  // the data line into tokens up to its newline or comment.
  tokens_.clear();
  const char* const begin = text_.data();
  const char* const stop = begin + text_.size();
  const char* p = begin + pos_;
  while (p < stop) {
    while (p < stop && is_space(*p)) ++p;
    if (p == stop) break;
    if (*p == '\n') {
      ++p;
      ++next_line_;
      continue;
    }
    if (*p == '#') {
      const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(stop - p));
      if (nl == nullptr) break;
      p = static_cast<const char*>(nl) + 1;
      ++next_line_;
      continue;
    }
    // A data line.
    while (p < stop && *p != '\n') {
      const char* start = p;
      while (p < stop && !is_space(*p) && *p != '#' && *p != '\n') ++p;
      tokens_.emplace_back(start, static_cast<std::size_t>(p - start));
      while (p < stop && is_space(*p)) ++p;
      if (p < stop && *p == '#') {
        const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(stop - p));
        p = nl == nullptr ? stop : static_cast<const char*>(nl);
      }
    }
    line_ = next_line_;
    ++next_line_;
    pos_ = p < stop ? static_cast<std::size_t>(p - begin) + 1 : text_.size();
    return true;
  }
  pos_ = text_.size();
  return false;
}

bool TextReader::try_point_line(long long expected_id, bool with_marker, double& x, double& y,
                                long long& marker) {
  const char* p = text_.data() + pos_;
  const char* const stop = text_.data() + text_.size();
  auto skip_blanks = [&] {
    while (p < stop && (*p == ' ' || *p == '\t')) ++p;
  };
  skip_blanks();
  long long id;
  auto r = std::from_chars(p, stop, id);
  if (r.ec != std::errc() || id != expected_id) return false;
  p = r.ptr;
  for (double* out : {&x, &y}) {
    if (p == stop || (*p != ' ' && *p != '\t')) return false;
    skip_blanks();
    const auto d = std::from_chars(p, stop, *out);
    if (d.ec != std::errc() || !(*out - *out == 0.0)) return false;
    p = d.ptr;
  }
  if (with_marker) {
    if (p == stop || (*p != ' ' && *p != '\t')) return false;
    skip_blanks();
    r = std::from_chars(p, stop, marker);
    if (r.ec != std::errc()) return false;
    p = r.ptr;
  }
  while (p < stop && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  if (p < stop && *p != '\n') return false;
  line_ = next_line_;
  ++next_line_;
  tokens_.clear();
  pos_ = p < stop ? static_cast<std::size_t>(p - text_.data()) + 1 : text_.size();
  return true;
}

std::size_t TextReader::last_line() const {
  std::size_t n = 0;
  for (const char c : text_) n += c == '\n';
  // A last line without a final newline counts too.
  if (!text_.empty() && text_.back() != '\n') ++n;
  return n == 0 ? 1 : n;
}

std::size_t TextReader::count_data_lines_left() const {
  std::size_t n = 0;
  std::size_t p = pos_;
  while (p < text_.size()) {
    const std::size_t end = line_end(p);
    n += holds_data(p, end);
    p = end + 1;
  }
  return n;
}

namespace {

// A token as it may appear in a message: bytes outside printable ASCII as
// \xHH (a binary file must not put control characters or a NUL, which
// would cut the message, on the user's terminal), and at most 40 bytes of
// it (a token can be a whole megabyte of a corrupt file).
std::string printable_token(std::string_view token) {
  constexpr std::size_t kMax = 40;
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (token.size() > kMax) out += "...";
  return out;
}

}  // namespace

void TextReader::number_error(std::size_t i, NumberStatus s, const std::string& what) const {
  std::string msg = "'";
  msg += printable_token(tokens_[i]);
  switch (s) {
    case NumberStatus::NotAnInteger: msg += "' is not an integer"; break;
    case NumberStatus::OutOfRange: msg += "' is out of range"; break;
    default: msg += "' is not a number"; break;
  }
  msg += " (expected " + what + ")";
  fail(msg);
}

void TextReader::not_finite_error(std::size_t i, const std::string& what) const {
  fail(what + " is not finite ('" + printable_token(tokens_[i]) + "')");
}

}  // namespace deltamesh::io
