// Floating-point std::from_chars / std::to_chars, or a portable fallback
// where the standard library lacks them. Emscripten 3.1.6's libc++ (the web
// build, web/) has only the integer overloads; that build defines
// DELTAMESH_PORTABLE_FLOAT_CHARS and gets strtod / snprintf instead. Every
// other build calls the std functions directly (these inline to them), so
// the native readers and writers keep their speed and exact shortest output.
#pragma once
#include <charconv>
#include <system_error>

#ifdef DELTAMESH_PORTABLE_FLOAT_CHARS
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#endif

// The two versions live in different inline namespaces, so a test can
// compile the fallback next to a library built without it (no ODR clash).
namespace deltamesh::chars {

#ifndef DELTAMESH_PORTABLE_FLOAT_CHARS
inline namespace native {

inline std::from_chars_result parse_double(const char* first, const char* last, double& value) {
  return std::from_chars(first, last, value, std::chars_format::general);
}
// The shortest decimal that reads back as the same double.
inline std::to_chars_result shortest(char* first, char* last, double value) {
  return std::to_chars(first, last, value);
}
inline std::to_chars_result fixed(char* first, char* last, double value, int decimals) {
  return std::to_chars(first, last, value, std::chars_format::fixed, decimals);
}
inline std::to_chars_result general(char* first, char* last, double value, int precision) {
  return std::to_chars(first, last, value, std::chars_format::general, precision);
}

}  // namespace native
#else
inline namespace portable {

// from_chars' grammar (no leading blanks or '+', no hexadecimal) is kept by
// handing strtod only the longest prefix made of decimal-number characters.
inline std::from_chars_result parse_double(const char* first, const char* last, double& value) {
  const char* end = first;
  if (end != last && *end == '-') ++end;
  while (end != last) {
    const char c = *end;
    const bool number_char = (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' ||
                             c == '-' || c == 'i' || c == 'I' || c == 'n' || c == 'N' || c == 'f' || c == 'F' ||
                             c == 't' || c == 'T' || c == 'y' || c == 'Y' || c == 'a' || c == 'A';
    if (!number_char) break;
    ++end;
  }
  const std::string text(first, end);
  if (text.empty() || text[0] == '+') return {first, std::errc::invalid_argument};
  char* stop = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &stop);
  if (stop == text.c_str()) return {first, std::errc::invalid_argument};
  const char* ptr = first + (stop - text.c_str());
  if (errno == ERANGE && (std::isinf(v) || v == 0.0)) return {ptr, std::errc::result_out_of_range};
  value = v;
  return {ptr, std::errc()};
}

inline std::to_chars_result put(char* first, char* last, const char* format, int precision, double value) {
  const int n = std::snprintf(first, static_cast<std::size_t>(last - first), format, precision, value);
  if (n < 0 || n >= last - first) return {last, std::errc::value_too_large};
  return {first + n, std::errc()};
}

// The fewest significant digits (15 to 17) that read back as the same double.
inline std::to_chars_result shortest(char* first, char* last, double value) {
  for (int precision = 15; precision < 17; ++precision) {
    char buf[40];
    const int n = std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (n > 0 && std::strtod(buf, nullptr) == value) return put(first, last, "%.*g", precision, value);
  }
  return put(first, last, "%.*g", 17, value);
}
inline std::to_chars_result fixed(char* first, char* last, double value, int decimals) {
  return put(first, last, "%.*f", decimals, value);
}
inline std::to_chars_result general(char* first, char* last, double value, int precision) {
  return put(first, last, "%.*g", precision, value);
}

}  // namespace portable
#endif

}  // namespace deltamesh::chars
