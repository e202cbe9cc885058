#include "aesim/files/npy_header.hpp"

#include <cctype>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

std::size_t little_endian(const unsigned char* p, int bytes) {
  std::size_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= std::size_t(p[i]) << (8 * i);
  return v;
}

std::size_t skip_blanks(const std::string& text, std::size_t at) {
  while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  return at;
}

// The text after `'key':` (or "key":), blanks skipped; npos when the key is absent. Only a key
// followed by its colon counts: a structured dtype's field may carry the same name ('shape',
// "[('shape', '<i2')]"), followed by a comma.
std::size_t value_of(const std::string& dict, const char* key) {
  for (const char quote : {'\'', '"'}) {
    const std::string quoted = fmt::format("{0}{1}{0}", quote, key);
    for (std::size_t at = dict.find(quoted); at != std::string::npos; at = dict.find(quoted, at + 1)) {
      const std::size_t colon = skip_blanks(dict, at + quoted.size());
      if (colon < dict.size() && dict[colon] == ':') return skip_blanks(dict, colon + 1);
    }
  }
  return std::string::npos;
}

}  // namespace

NpyHeader parse_npy_header(const std::string& data, const std::string& what) {
  const auto fail = [&](const std::string& why) { return InputError(fmt::format("{}: {}", what, why)); };
  if (data.size() < 10 || data.compare(0, 6, kNpyMagic, 6) != 0) throw fail("not a NumPy .npy file");
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  const int major = bytes[6];
  std::size_t length = 0, at = 0;
  if (major == 1) {
    length = little_endian(bytes + 8, 2);
    at = 10;
  } else if (major == 2 || major == 3) {
    if (data.size() < 12) throw fail("truncated .npy header");
    length = little_endian(bytes + 8, 4);
    at = 12;
  } else {
    throw fail(fmt::format(".npy format version {} is not supported", major));
  }
  if (length > data.size() - at) throw fail("truncated .npy header");
  const std::string dict = data.substr(at, length);
  NpyHeader header;
  header.data_offset = at + length;

  const std::size_t descr = value_of(dict, "descr");
  if (descr == std::string::npos || descr >= dict.size()) throw fail("the .npy header has no dtype");
  if (dict[descr] == '[') {
    // A structured dtype: its list, brackets balanced (a field may hold a sub-array's shape).
    int depth = 0;
    std::size_t end = descr;
    for (; end < dict.size(); ++end) {
      if (dict[end] == '[') ++depth;
      if (dict[end] == ']' && --depth == 0) break;
    }
    if (end == dict.size()) throw fail("malformed .npy dtype");
    header.descr = dict.substr(descr, end - descr + 1);
  } else if (dict[descr] == '\'' || dict[descr] == '"') {
    const std::size_t end = dict.find(dict[descr], descr + 1);
    if (end == std::string::npos) throw fail("malformed .npy dtype");
    header.descr = dict.substr(descr + 1, end - descr - 1);
  } else {
    throw fail("malformed .npy dtype");
  }

  const std::size_t order = value_of(dict, "fortran_order");
  if (order == std::string::npos) throw fail("the .npy header has no fortran_order");
  if (dict.compare(order, 4, "True") == 0) {
    header.fortran_order = true;
  } else if (dict.compare(order, 5, "False") != 0) {
    throw fail("malformed .npy fortran_order");
  }

  const std::size_t shape = value_of(dict, "shape");
  if (shape == std::string::npos || shape >= dict.size() || dict[shape] != '(') throw fail("the .npy header has no shape");
  const std::size_t close = dict.find(')', shape);
  if (close == std::string::npos) throw fail("malformed .npy shape");
  // "(64, 48)", "(5,)", "()": numbers each followed by a comma or the closing parenthesis.
  std::size_t p = shape + 1;
  while (true) {
    p = skip_blanks(dict, p);
    if (p >= close) break;
    if (!std::isdigit(static_cast<unsigned char>(dict[p]))) throw fail("malformed .npy shape");
    std::uint64_t n = 0;
    for (; p < close && std::isdigit(static_cast<unsigned char>(dict[p])); ++p) {
      if (n > (UINT64_MAX - 9) / 10) throw fail("a .npy dimension beyond 2^64");
      n = n * 10 + static_cast<std::uint64_t>(dict[p] - '0');
    }
    header.shape.push_back(n);
    if (p < close && dict[p] == 'L') ++p;  // Python 2's long integers
    p = skip_blanks(dict, p);
    if (p < close && dict[p] == ',') {
      ++p;
    } else if (p != close) {
      throw fail("malformed .npy shape");
    }
  }
  return header;
}

}  // namespace aesim
