#include "io/text_reader.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sys/mman.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>

#include <cmath>
#include <cstring>
#include <limits>
#include <system_error>

#include "core/parallel.hpp"
#include "core/prefault.hpp"
#include "core/float_chars.hpp"

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

namespace {

void throw_read_error(const std::string& path, int err) {
  throw IoError("cannot read '" + path + "': " + errno_text(err));
}

// Opens `path` for reading and checks it is not a directory.
int open_for_reading(const std::string& path, struct stat& st) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError("cannot open '" + path + "': " + errno_text(errno));
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    throw_read_error(path, err);
  }
  if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw_read_error(path, EISDIR);
  }
  return fd;
}

std::string read_all(int fd, const struct stat& st, const std::string& path) {
  std::string text;
  // Regular files: one read of the known size. Pipes and growing files: the
  // buffer grows until end of file.
  std::size_t capacity = S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : 65536;
  text.resize(capacity);
  std::size_t used = 0;
  for (;;) {
    if (used == text.size()) text.resize(text.size() * 2);
    const ssize_t got = ::read(fd, text.data() + used, text.size() - used);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw_read_error(path, errno);
    }
    if (got == 0) break;
    used += static_cast<std::size_t>(got);
  }
  text.resize(used);
  return text;
}

}  // namespace

std::string read_whole_file(const std::string& path) {
  struct stat st {};
  Fd fd(open_for_reading(path, st));
  return read_all(fd.get(), st, path);
}

namespace {

constexpr bool is_digit(char c) { return static_cast<unsigned char>(c - '0') < 10; }

// Eight ASCII digits at p (little-endian load): whether they are all digits,
// and their value. Each step merges neighbouring lanes: bytes into 2-digit
// numbers, those into 4-digit, those into the 8-digit value.
std::uint64_t load8(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}
bool eight_digits(std::uint64_t v) {
  const std::uint64_t below = v - 0x3030303030303030u;  // high bit set where a byte < '0'
  const std::uint64_t above = v + 0x4646464646464646u;  // high bit set where a byte > '9'
  return ((below | above) & 0x8080808080808080u) == 0;
}
std::uint64_t value8(std::uint64_t v) {
  v -= 0x3030303030303030u;
  v = (v * 10 + (v >> 8)) & 0x00FF00FF00FF00FFu;
  v = (v * 100 + (v >> 16)) & 0x0000FFFF0000FFFFu;
  return (v * 10000 + (v >> 32)) & 0xFFFFFFFFu;
}

constexpr bool kSwar = std::endian::native == std::endian::little;
constexpr int kMaxDigits = 19;  // 10^19 - 1 < 2^64

// Appends the digits at p to m (at most kMaxDigits significant digits in
// all; `significant` counts them). Returns the end of the digits, or nullptr
// when there are too many.
[[gnu::always_inline]] inline const char* accumulate_digits(const char* p, const char* last, std::uint64_t& m,
                                                           int& significant) {
  if (m == 0)  // leading zeros are not significant
    while (p < last && *p == '0') ++p;
  if constexpr (kSwar) {
    while (last - p >= 8 && significant + 8 <= kMaxDigits) {
      const std::uint64_t v = load8(p);
      if (!eight_digits(v)) break;
      m = m * 100000000u + value8(v);
      significant += 8;
      p += 8;
    }
  }
  while (p < last && is_digit(*p)) {
    if (++significant > kMaxDigits) return nullptr;
    m = m * 10 + static_cast<unsigned>(*p - '0');
    ++p;
  }
  return p;
}

constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                             1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
// 10^k = 2^k 5^k is exact in 64 bits of significand up to k = 27 (5^27 < 2^63).
constexpr bool kX87 = std::numeric_limits<long double>::digits == 64 && kSwar;
constexpr long double kPow10L[] = {1e0L,  1e1L,  1e2L,  1e3L,  1e4L,  1e5L,  1e6L,  1e7L,  1e8L,  1e9L,
                                   1e10L, 1e11L, 1e12L, 1e13L, 1e14L, 1e15L, 1e16L, 1e17L, 1e18L, 1e19L,
                                   1e20L, 1e21L, 1e22L, 1e23L, 1e24L, 1e25L, 1e26L, 1e27L};

}  // namespace

const char* parse_decimal_prefix(const char* first, const char* last, double& value) {
  const char* p = first;
  const bool negative = p < last && *p == '-';
  p += negative;
  std::uint64_t m = 0;
  int significant = 0;
  const char* const int_start = p;
  p = accumulate_digits(p, last, m, significant);
  if (p == nullptr) return nullptr;
  bool any_digit = p != int_start;
  int exponent = 0;
  if (p < last && *p == '.') {
    const char* const frac_start = ++p;
    p = accumulate_digits(p, last, m, significant);
    if (p == nullptr) return nullptr;
    exponent = -static_cast<int>(p - frac_start);
    any_digit = any_digit || p != frac_start;
  }
  if (!any_digit) return nullptr;
  if (p < last && (*p == 'e' || *p == 'E')) {
    const char* q = p + 1;
    const bool exp_negative = q < last && *q == '-';
    if (q < last && (*q == '-' || *q == '+')) ++q;
    if (q == last || !is_digit(*q)) return nullptr;  // "1e": from_chars stops before the 'e'
    int e = 0;
    for (; q < last && is_digit(*q); ++q)
      if (e < 100000) e = e * 10 + (*q - '0');
    exponent += exp_negative ? -e : e;
    p = q;
  }
  double v;
  if (m == 0) {
    v = 0.0;
  } else if (m <= (std::uint64_t{1} << 53) && exponent >= -22 && exponent <= 22) {
    // Clinger: both operands exact, so the one rounding is the correct one.
    v = exponent < 0 ? static_cast<double>(m) / kPow10[-exponent] : static_cast<double>(m) * kPow10[exponent];
  } else if (kX87 && exponent >= -27 && exponent <= 27) {
    // Exact operands again; the result is rounded to 64 bits, then to 53.
    // Rounding twice can differ from rounding once only when the first
    // result lies exactly half-way between two doubles (its low 11 bits are
    // 10000000000): those go to from_chars. The result is far from the
    // subnormal range, where the double grid would change.
    const auto y = static_cast<long double>(m);
    const long double r = exponent < 0 ? y / kPow10L[-exponent] : y * kPow10L[exponent];
    std::uint64_t significand;
    std::memcpy(&significand, &r, sizeof significand);
    if ((significand & 0x7FF) == 0x400) return nullptr;
    v = static_cast<double>(r);
  } else {
    return nullptr;
  }
  value = negative ? -v : v;
  return p;
}

NumberStatus parse_double(std::string_view token, double& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  if (parse_decimal_prefix(first, last, value) == last) return NumberStatus::Ok;
  const bool plus = first != last && *first == '+';
  if (plus) ++first;
  if (first == last || (plus && (*first == '+' || *first == '-'))) return NumberStatus::NotANumber;
  const auto [ptr, ec] = chars::parse_double(first, last, value);
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
    : file_(std::move(file_name)), owned_(std::move(text)), text_(owned_) {
  tokens_.reserve(16);
  // A UTF-8 byte order mark (some Windows editors write one) is not data.
  if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
}

TextReader::TextReader(std::string file_name, Mapping mapping)
    : file_(std::move(file_name)),
      mapping_(mapping),
      text_(static_cast<const char*>(mapping.address), mapping.length) {
  tokens_.reserve(16);
  if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
}

TextReader::~TextReader() {
  if (mapping_.address != nullptr) ::munmap(mapping_.address, mapping_.length);
}

TextReader TextReader::open(const std::string& path) {
  struct stat st {};
  Fd fd(open_for_reading(path, st));
  // Mapping a file in the page cache costs neither a copy nor a zero-filled
  // buffer (together about a third of reading a large .node file). A file
  // truncated by another process while we parse it would fault; files being
  // rewritten under a mesher are not a use we support. Empty regular files
  // (and /proc files, which report size 0) are read.
  if (S_ISREG(st.st_mode) && st.st_size > 0) {
    int flags = MAP_PRIVATE;
#ifdef MAP_POPULATE
    flags |= MAP_POPULATE;  // map every page now rather than fault on each
#endif
    const auto length = static_cast<std::size_t>(st.st_size);
    void* address = ::mmap(nullptr, length, PROT_READ, flags, fd.get(), 0);
    if (address != MAP_FAILED) return TextReader(path, Mapping{address, length});
  }
  return TextReader(path, read_all(fd.get(), st, path));
}

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

namespace {

// A plain unsigned decimal of at most 18 digits at p; nullptr for anything
// else (signs, longer numbers: the caller falls back to the general path).
const char* parse_small_unsigned(const char* p, const char* last, long long& value) {
  const char* const start = p;
  long long v = 0;
  while (p < last && is_digit(*p) && p - start < 18) v = v * 10 + (*p++ - '0');
  if (p == start || (p < last && is_digit(*p))) return nullptr;
  value = v;
  return p;
}

}  // namespace

bool TextReader::try_point_line(long long expected_id, bool with_marker, double& x, double& y,
                                long long& marker) {
  const char* p = text_.data() + pos_;
  const char* const stop = text_.data() + text_.size();
  auto skip_blanks = [&] {
    while (p < stop && (*p == ' ' || *p == '\t')) ++p;
  };
  skip_blanks();
  long long id;
  p = parse_small_unsigned(p, stop, id);
  if (p == nullptr || id != expected_id) return false;
  for (double* out : {&x, &y}) {
    if (p == stop || (*p != ' ' && *p != '\t')) return false;
    skip_blanks();
    const char* end = parse_decimal_prefix(p, stop, *out);
    if (end == nullptr) {
      const auto d = chars::parse_double(p, stop, *out);
      if (d.ec != std::errc()) return false;
      end = d.ptr;
    }
    if (!(*out - *out == 0.0)) return false;
    p = end;
  }
  if (with_marker) {
    if (p == stop || (*p != ' ' && *p != '\t')) return false;
    skip_blanks();
    const auto r = std::from_chars(p, stop, marker);
    // A marker outside int is an error the general path words.
    if (r.ec != std::errc() || marker != static_cast<int>(marker)) return false;
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

bool TextReader::try_point_lines(long long first_id, std::size_t count, bool with_marker, unsigned threads,
                                 std::vector<Point>& points, std::vector<int>& markers) {
  if (count == 0) return true;
  // A piece: lines parsed from a line start until one is not a point line
  // or the piece ends; ids consecutive from the first line's own. The first
  // piece appends to `points` and `markers` themselves (no copy at the
  // join), the others to their own vectors.
  struct Piece {
    std::size_t begin = 0, end = 0;  // byte range, both at line starts
    long long first = -1;            // id of its first line
    std::size_t parsed = 0;          // point lines from its start
    std::size_t stop = 0;            // where parsing stopped
    std::vector<Point> points;
    std::vector<int> markers;
  };
  const std::size_t points_before = points.size(), markers_before = markers.size();
  const std::size_t total = text_.size() - pos_;
  const std::size_t pieces = std::max<std::size_t>(1, std::min<std::size_t>(threads, total / (1u << 20)));
  std::vector<Piece> part(pieces);
  for (std::size_t j = 0; j < pieces; ++j) {
    std::size_t b = pos_ + total * j / pieces;
    if (j > 0) b = std::min(text_.size(), line_end(b) + 1);  // the next line start
    part[j].begin = b;
  }
  for (std::size_t j = 0; j < pieces; ++j) part[j].end = j + 1 < pieces ? part[j + 1].begin : text_.size();
  // Where the pieces after the first will be copied at the join (serial):
  // their pages of the reserved capacity are faulted in beforehand, each by
  // its piece's thread (see prefault_for_write). Taken before the first
  // piece appends; only when the reserve holds every line (no reallocation).
  Point* const points_at = points.capacity() >= points_before + count ? points.data() + points_before : nullptr;
  int* const markers_at =
      with_marker && markers.capacity() >= markers_before + count ? markers.data() + markers_before : nullptr;
  detail::run_tasks(pieces, threads, [&](std::size_t j) {
    Piece& q = part[j];
    if (q.begin >= q.end) return;
    std::vector<Point>& out = j == 0 ? points : q.points;
    std::vector<int>& out_markers = j == 0 ? markers : q.markers;
    // A reader over the piece, sharing the text (no copy).
    TextReader r(file_, Mapping{});
    r.text_ = text_.substr(0, q.end);
    r.pos_ = q.begin;
    const char* p = r.text_.data() + q.begin;
    const char* const stop = r.text_.data() + r.text_.size();
    while (p < stop && (*p == ' ' || *p == '\t')) ++p;
    if (parse_small_unsigned(p, stop, q.first) == nullptr) return;
    if (j > 0) q.points.reserve((q.end - q.begin) / 16 + 1);
    double x, y;
    long long m = 0;
    while (r.pos_ < q.end && r.try_point_line(q.first + static_cast<long long>(q.parsed), with_marker, x, y, m)) {
      out.push_back({x, y});
      if (with_marker) out_markers.push_back(static_cast<int>(m));
      ++q.parsed;
    }
    q.stop = r.pos_;
    if (j > 0) {  // its lines' likely place among the count, with a margin
      const std::size_t from = count * (q.begin - pos_) / total, to = count * (q.end - pos_) / total;
      const std::size_t lo = from - std::min(from, count / 64), hi = std::min(count, to + count / 64);
      if (points_at) detail::prefault_for_write(points_at + lo, (hi - lo) * sizeof(Point));
      if (markers_at) detail::prefault_for_write(markers_at + lo, (hi - lo) * sizeof(int));
    }
  });
  // Joined in order: each piece must go on from where the previous one
  // ended, and the lines wanted must all have been point lines.
  std::size_t got = 0;
  long long next = first_id;
  std::size_t end_pos = pos_;
  bool all = true;
  for (const Piece& q : part) {
    if (got == count) break;
    if (q.begin >= q.end) continue;
    const std::size_t need = count - got;
    if (q.first != next || (q.parsed < need && q.stop != q.end)) {
      all = false;
      break;
    }
    const std::size_t take = std::min(need, q.parsed);
    got += take;
    next += static_cast<long long>(take);
  }
  if (!all || got != count) {
    points.resize(points_before);
    markers.resize(markers_before);
    return false;
  }
  // Commit: the values, and the position after the last line taken.
  got = 0;
  for (std::size_t j = 0; j < pieces; ++j) {
    const Piece& q = part[j];
    if (got == count) break;
    if (q.begin >= q.end) continue;
    const std::size_t take = std::min(count - got, q.parsed);
    if (j == 0) {
      points.resize(points_before + take);
      if (with_marker) markers.resize(markers_before + take);
    } else {
      points.insert(points.end(), q.points.begin(), q.points.begin() + static_cast<std::ptrdiff_t>(take));
      if (with_marker)
        markers.insert(markers.end(), q.markers.begin(), q.markers.begin() + static_cast<std::ptrdiff_t>(take));
    }
    end_pos = q.stop;
    if (take < q.parsed) {  // the block ends inside this piece: find the end of its last line
      end_pos = q.begin;
      for (std::size_t k = 0; k < take; ++k) end_pos = std::min(text_.size(), line_end(end_pos) + 1);
    }
    got += take;
  }
  pos_ = end_pos;
  line_ = next_line_ + count - 1;
  next_line_ += count;
  tokens_.clear();
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
