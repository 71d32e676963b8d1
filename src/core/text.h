// Small string helpers shared by the readers and writers.
#pragma once

#include <cctype>
#include <cstdio>
#include <string>

namespace isoquad {

// `text` in lower case (ASCII), for file extensions and format names.
inline std::string lower_case(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

inline bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() &&
         text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// printf into a string (give at least one argument after the format).
template <typename... Args>
std::string printf_string(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  std::string text(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

// The length of the valid UTF-8 sequence that starts at text[i] (1 for ASCII), or 0 when
// the bytes there are not one (a stray continuation byte, an overlong or truncated
// sequence, a surrogate, beyond U+10FFFF).
std::size_t utf8_sequence_length(const std::string& text, std::size_t i);

bool is_utf8(const std::string& text);

// `text` as valid UTF-8: each byte that starts no valid UTF-8 sequence read as
// Windows-1252 (Latin-1 and more: the usual encoding of a .dbf without its .cpg), its five
// unassigned bytes as U+FFFD. Valid UTF-8 is returned as it is.
std::string utf8_or_cp1252(const std::string& text);

}  // namespace isoquad
