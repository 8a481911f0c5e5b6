// The web build's number conversions through JavaScript (see
// float_chars.hpp); empty in every other build.
#include "core/float_chars.hpp"

#if defined(DELTAMESH_PORTABLE_FLOAT_CHARS) && defined(__EMSCRIPTEN__)
#include <emscripten/emscripten.h>

// `text` holds exactly a decimal number (parse_double checked its grammar).
EM_JS(double, deltamesh_js_parse, (const char* text, int length), {
  return Number(UTF8ToString(text, length));
});

// ECMAScript's Number::toString: the shortest decimal that reads back as
// the same double.
EM_JS(int, deltamesh_js_shortest, (double value, char* out, int capacity), {
  const s = String(value);
  if (s.length >= capacity) return -1;
  stringToUTF8(s, out, capacity);
  return s.length;
});

namespace deltamesh::chars {
inline namespace portable {

// Real functions, so that the linker takes this object (and the JavaScript
// above) from the static library.
double js_parse(const char* text, int length) { return deltamesh_js_parse(text, length); }
int js_shortest(double value, char* out, int capacity) { return deltamesh_js_shortest(value, out, capacity); }

}  // namespace portable
}  // namespace deltamesh::chars
#endif
