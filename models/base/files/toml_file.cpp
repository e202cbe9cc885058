#include "aesim/files/toml_file.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>

#include <fmt/format.h>
#include <toml.hpp>

namespace aesim {
namespace {

constexpr std::uintmax_t kMaxTomlBytes = 1 << 20;

// Length of the valid UTF-8 sequence starting at s[i], or 0 if it is not one (RFC 3629 table 3).
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
  const unsigned c = byte(i);
  auto cont = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) { return byte(k) >= lo && byte(k) <= hi; };
  if (c < 0x80) return 1;
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1) ? 2 : 0;
  if (c == 0xE0) return cont(i + 1, 0xA0) && cont(i + 2) ? 3 : 0;
  if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) return cont(i + 1) && cont(i + 2) ? 3 : 0;
  if (c == 0xED) return cont(i + 1, 0x80, 0x9F) && cont(i + 2) ? 3 : 0;  // no surrogates
  if (c == 0xF0) return cont(i + 1, 0x90) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  if (c >= 0xF1 && c <= 0xF3) return cont(i + 1) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  if (c == 0xF4) return cont(i + 1, 0x80, 0x8F) && cont(i + 2) && cont(i + 3) ? 4 : 0;
  return 0;
}

constexpr int kMaxNesting = 32;
constexpr int kMaxBinaryDigits = 62;

// Two defects of toml11 3.7.1 that the fuzzer found, refused here before the parser runs:
// - it parses nested arrays and inline tables by recursion, one level per bracket, so a file of
//   "[[[[..." overflows the stack: brackets and braces may nest at most kMaxNesting deep (a table
//   header [[a]] takes two);
// - it reads a binary integer by doubling a signed 64-bit place value once per digit, which
//   overflows (undefined behaviour) past 62 digits, leading zeros included: longer 0b literals
//   are refused. (Octal and hexadecimal go through a stream, which fails safely.)
// Both are checked outside strings and comments only.
void check_structure(const std::string& text, const std::string& label) {
  int depth = 0;
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
    } else if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const std::string triple(3, c);
      const bool multi = text.compare(i, 3, triple) == 0;
      const std::string close = multi ? triple : std::string(1, c);
      std::size_t j = i + close.size();
      while (j < text.size() && text.compare(j, close.size(), close) != 0 && (multi || text[j] != '\n')) {
        if (c == '"' && text[j] == '\\') ++j;  // an escape in a basic string
        if (j < text.size() && text[j] == '\n') ++line;
        ++j;
      }
      i = std::min(text.size(), j + close.size()) - 1;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxNesting) {
        throw InputError(fmt::format("{}: line {}: arrays or tables nested deeper than {}", label, line, kMaxNesting));
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    } else if (c == '0' && i + 1 < text.size() && text[i + 1] == 'b' &&
               (i == 0 || std::string_view(" \t=[,{+-").find(text[i - 1]) != std::string_view::npos)) {
      int digits = 0;
      std::size_t j = i + 2;
      for (; j < text.size() && (text[j] == '0' || text[j] == '1' || text[j] == '_'); ++j) digits += text[j] != '_';
      if (digits > kMaxBinaryDigits) {
        throw InputError(fmt::format("{}: line {}: binary integer of {} digits (at most {})", label, line, digits,
                                     kMaxBinaryDigits));
      }
      i = j - 1;
    }
  }
}

}  // namespace

std::string checked_toml_text(const std::string& path, const std::string& label) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(fmt::format("{}: cannot read: {}", label, ec.message()));
  if (size > kMaxTomlBytes) throw InputError(fmt::format("{}: {} bytes, more than the 1 MiB a TOML file may have", label, size));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read", label));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  check_toml_text(text, label);
  return text;
}

void check_toml_text(const std::string& text, const std::string& label) {
  if (text.size() > kMaxTomlBytes) {
    throw InputError(fmt::format("{}: {} bytes, more than the 1 MiB a TOML file may have", label, text.size()));
  }
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n') ++line;
    if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7F) {
      throw InputError(fmt::format("{}: line {}: control character 0x{:02X} (TOML allows only tab and newlines)", label,
                                   line, c));
    }
    const std::size_t n = utf8_length(text, i);
    if (n == 0) throw InputError(fmt::format("{}: line {}: invalid UTF-8 byte 0x{:02X}", label, line, c));
    i += n;
  }
  check_structure(text, label);
}

std::optional<std::string> TomlValue::scalar_text() const {
  switch (kind_) {
    case Kind::String: return string_;
    case Kind::Integer: return std::to_string(integer_);
    case Kind::Floating: return fmt::format("{:.17g}", floating_);
    case Kind::Boolean: return std::string(boolean_ ? "true" : "false");
    default: return std::nullopt;
  }
}

// Copies toml11's tree into TomlValue.
class TomlReader {
 public:
  using Toml = toml::basic_value<toml::discard_comments, std::map, std::vector>;
  static TomlValue read(const Toml& v) {
    TomlValue out;
    if (v.is_string()) {
      out.kind_ = TomlValue::Kind::String;
      out.string_ = v.as_string().str;
    } else if (v.is_integer()) {
      out.kind_ = TomlValue::Kind::Integer;
      out.integer_ = v.as_integer();
    } else if (v.is_floating()) {
      out.kind_ = TomlValue::Kind::Floating;
      out.floating_ = v.as_floating();
    } else if (v.is_boolean()) {
      out.kind_ = TomlValue::Kind::Boolean;
      out.boolean_ = v.as_boolean();
    } else if (v.is_table()) {
      out.kind_ = TomlValue::Kind::Table;
      for (const auto& [key, value] : v.as_table()) out.table_.emplace(key, read(value));
    } else if (v.is_array()) {
      out.kind_ = TomlValue::Kind::Array;
      for (const Toml& item : v.as_array()) out.array_.push_back(read(item));
    }
    return out;
  }
};

TomlValue parse_toml_text(const std::string& text, const std::string& label) {
  check_toml_text(text, label);
  std::istringstream in(text);
  TomlReader::Toml doc;
  try {
    doc = toml::parse<toml::discard_comments, std::map, std::vector>(in, label);
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    throw InputError(label + ": malformed TOML: " + msg.substr(0, msg.find('\n')));
  }
  return TomlReader::read(doc);
}

TomlValue parse_toml_file(const std::string& path, const std::string& label) {
  return parse_toml_text(checked_toml_text(path, label), label);
}

}  // namespace aesim
