#include "config/toml_file.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

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
}

}  // namespace aesim
