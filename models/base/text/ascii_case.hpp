#pragma once
#include <cctype>
#include <string>

namespace aesim {

// Lower case for keys, keywords and SPICE names: ASCII only, whatever the locale.
inline std::string ascii_lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace aesim
