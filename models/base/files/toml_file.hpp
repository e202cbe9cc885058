#pragma once
#include <sstream>
#include <string>

#include <toml.hpp>

#include "errors/input_error.hpp"

namespace aesim {

// The text of a TOML file, checked before toml11 sees it. Debian's toml11 3.7.1 reads past its
// buffer on a literal string holding an invalid UTF-8 byte (its upstream issue 199), so every
// byte sequence must be valid UTF-8 (RFC 3629: no overlong forms, no surrogates) and free of the
// control characters TOML forbids (all but tab, LF and CR). Files over 1 MiB are refused too, and
// two shapes that crash toml11 (found by the fuzzer): arrays and inline tables nested more than 32
// deep, and binary integers of more than 62 digits.
// `label` names the file in messages, e.g. "sweep spec 'x.toml'". Throws InputError naming the
// line and the byte.
std::string checked_toml_text(const std::string& path, const std::string& label);
// The same check on text already in memory.
void check_toml_text(const std::string& text, const std::string& label);

// Parses checked TOML text (toml11's parse with its template arguments); malformed TOML is an
// InputError with toml11's first message line.
template <typename Comment = toml::discard_comments, template <typename...> class Table = std::unordered_map,
          template <typename...> class Array = std::vector>
toml::basic_value<Comment, Table, Array> parse_toml_text(const std::string& text, const std::string& label) {
  check_toml_text(text, label);
  std::istringstream in(text);
  try {
    return toml::parse<Comment, Table, Array>(in, label);
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    throw InputError(label + ": malformed TOML: " + msg.substr(0, msg.find('\n')));
  }
}

template <typename Comment = toml::discard_comments, template <typename...> class Table = std::unordered_map,
          template <typename...> class Array = std::vector>
toml::basic_value<Comment, Table, Array> parse_toml_file(const std::string& path, const std::string& label) {
  return parse_toml_text<Comment, Table, Array>(checked_toml_text(path, label), label);
}

}  // namespace aesim
