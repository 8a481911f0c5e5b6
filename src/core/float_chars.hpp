// Floating-point std::from_chars / std::to_chars, or a portable fallback
// where the standard library lacks them. Emscripten 3.1.6's libc++ (the web
// build, web/) has only the integer overloads; that build defines
// DELTAMESH_PORTABLE_FLOAT_CHARS and gets the fallback. Every other build
// calls the std functions directly (these inline to them), so the native
// readers and writers keep their speed and exact shortest output.
#pragma once
#include <charconv>
#include <system_error>

#ifdef DELTAMESH_PORTABLE_FLOAT_CHARS
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
// The shortest fixed-point form (no exponent) that reads back as the same double.
inline std::to_chars_result shortest_fixed(char* first, char* last, double value) {
  return std::to_chars(first, last, value, std::chars_format::fixed);
}

}  // namespace native
#else
// A too-small buffer is reported as to_chars does (value_too_large), so
// gcc's truncation warning about snprintf into small buffers is moot here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wformat-truncation"
#endif
inline namespace portable {

#ifdef __EMSCRIPTEN__
// JavaScript's own conversions (float_chars.cpp): Number() is correctly
// rounded and String(v) is the shortest round trip, while musl's strtod is
// slow in WebAssembly (its long double arithmetic is done in software).
double js_parse(const char* text, int length);
int js_shortest(double value, char* out, int capacity);  // -1: does not fit
#endif

inline bool ascii_iequal(const char* p, const char* last, const char* word) {
  for (; *word; ++p, ++word)
    if (p == last || (*p | 0x20) != *word) return false;
  return true;
}

// from_chars' grammar for chars_format::general: [-] then inf, infinity, nan
// or digits [. digits] [e [+-] digits] with at least one digit; no blanks,
// no '+', no hexadecimal. The decimal text found is then converted exactly.
inline std::from_chars_result parse_double(const char* first, const char* last, double& value) {
  const char* p = first;
  const bool negative = p != last && *p == '-';
  if (negative) ++p;
  if (ascii_iequal(p, last, "inf")) {
    value = negative ? -HUGE_VAL : HUGE_VAL;
    return {p + (ascii_iequal(p, last, "infinity") ? 8 : 3), std::errc()};
  }
  if (ascii_iequal(p, last, "nan")) {
    value = negative ? -NAN : NAN;
    return {p + 3, std::errc()};
  }
  const auto digit = [last](const char* q) { return q != last && *q >= '0' && *q <= '9'; };
  bool any = false, nonzero = false;
  for (; digit(p); ++p) any = true, nonzero |= *p != '0';
  if (p != last && *p == '.') {
    ++p;
    for (; digit(p); ++p) any = true, nonzero |= *p != '0';
  }
  if (!any) return {first, std::errc::invalid_argument};
  if (p != last && (*p == 'e' || *p == 'E')) {
    const char* q = p + 1;
    if (q != last && (*q == '+' || *q == '-')) ++q;
    if (digit(q)) {
      while (digit(q)) ++q;
      p = q;
    }
  }
#ifdef __EMSCRIPTEN__
  const double v = js_parse(first, static_cast<int>(p - first));
#else
  const double v = std::strtod(std::string(first, p).c_str(), nullptr);
#endif
  if (std::isinf(v) || (v == 0.0 && nonzero)) return {p, std::errc::result_out_of_range};
  value = v;
  return {p, std::errc()};
}

inline std::to_chars_result put(char* first, char* last, const char* format, int precision, double value) {
  const int n = std::snprintf(first, static_cast<std::size_t>(last - first), format, precision, value);
  if (n < 0 || n >= last - first) return {last, std::errc::value_too_large};
  return {first + n, std::errc()};
}

inline std::to_chars_result put_text(char* first, char* last, const char* text) {
  const std::size_t n = std::char_traits<char>::length(text);
  if (static_cast<std::size_t>(last - first) < n) return {last, std::errc::value_too_large};
  for (std::size_t i = 0; i < n; ++i) first[i] = text[i];
  return {first + n, std::errc()};
}

// The shortest decimal that reads back as the same double (to_chars may
// spell the same value otherwise: "1e-07" where this has "1e-7").
inline std::to_chars_result shortest(char* first, char* last, double value) {
  if (std::isnan(value)) return put_text(first, last, std::signbit(value) ? "-nan" : "nan");
  if (std::isinf(value)) return put_text(first, last, value < 0 ? "-inf" : "inf");
  if (value == 0.0) return put_text(first, last, std::signbit(value) ? "-0" : "0");
#ifdef __EMSCRIPTEN__
  const int n = js_shortest(value, first, static_cast<int>(last - first));
  if (n < 0) return {last, std::errc::value_too_large};
  return {first + n, std::errc()};
#else
  // The fewest significant digits (15 to 17) that read back exactly.
  for (int precision = 15; precision < 17; ++precision) {
    char buf[40];
    const int n = std::snprintf(buf, sizeof buf, "%.*g", precision, value);
    if (n > 0 && std::strtod(buf, nullptr) == value) return put(first, last, "%.*g", precision, value);
  }
  return put(first, last, "%.*g", 17, value);
#endif
}
inline std::to_chars_result fixed(char* first, char* last, double value, int decimals) {
  return put(first, last, "%.*f", decimals, value);
}
inline std::to_chars_result general(char* first, char* last, double value, int precision) {
  return put(first, last, "%.*g", precision, value);
}
// The fewest decimals that read back (for messages: a loop is fine).
inline std::to_chars_result shortest_fixed(char* first, char* last, double value) {
  char buf[400];
  for (int decimals = 0; decimals < 340; ++decimals) {
    const int n = std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    if (n > 0 && n < static_cast<int>(sizeof buf) && std::strtod(buf, nullptr) == value)
      return put(first, last, "%.*f", decimals, value);
  }
  return put(first, last, "%.*f", 339, value);
}

}  // namespace portable
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

}  // namespace deltamesh::chars
