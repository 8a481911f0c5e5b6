#pragma once
namespace deltamesh {
inline constexpr const char* kVersion = "0.1.0";
}
