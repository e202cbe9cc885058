#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "aesim/errors/input_error.hpp"

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

// A parsed TOML document as plain data, so that toml11 (seconds of compile time in every file
// that includes it) is compiled in toml_file.cpp alone. Tables keep their keys in sorted order.
class TomlValue {
 public:
  enum class Kind { String, Integer, Floating, Boolean, Table, Array, Other };

  Kind kind() const { return kind_; }
  bool is_string() const { return kind_ == Kind::String; }
  bool is_integer() const { return kind_ == Kind::Integer; }
  bool is_floating() const { return kind_ == Kind::Floating; }
  bool is_boolean() const { return kind_ == Kind::Boolean; }
  bool is_table() const { return kind_ == Kind::Table; }
  bool is_array() const { return kind_ == Kind::Array; }
  const std::string& as_string() const { return string_; }
  std::int64_t as_integer() const { return integer_; }
  double as_floating() const { return floating_; }
  bool as_boolean() const { return boolean_; }
  const std::map<std::string, TomlValue>& as_table() const { return table_; }
  const std::vector<TomlValue>& as_array() const { return array_; }
  // A scalar as a --set value would be written: a string as it is, an integer in decimal, a float
  // with 17 significant digits, a boolean as true or false; empty for tables, arrays and dates.
  std::optional<std::string> scalar_text() const;

 private:
  friend class TomlReader;
  Kind kind_ = Kind::Other;
  std::string string_;
  std::int64_t integer_ = 0;
  double floating_ = 0;
  bool boolean_ = false;
  std::map<std::string, TomlValue> table_;
  std::vector<TomlValue> array_;
};

// Parses checked TOML text; malformed TOML is an InputError with toml11's first message line.
TomlValue parse_toml_text(const std::string& text, const std::string& label);
TomlValue parse_toml_file(const std::string& path, const std::string& label);

}  // namespace aesim
