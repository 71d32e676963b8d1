// Small string helpers shared by the readers and writers.
#pragma once

#include <cctype>
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

}  // namespace isoquad
