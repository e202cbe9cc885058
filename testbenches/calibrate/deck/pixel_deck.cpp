#include "deck/pixel_deck.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "errors/input_error.hpp"
#include "text/ascii_case.hpp"
#include "files/input_path.hpp"

namespace aesim {
namespace {

namespace fs = std::filesystem;

// Decks are text of kilobytes; a PDK's model file can be megabytes. Beyond this it is not a deck.
constexpr std::uintmax_t kMaxDeckBytes = 64u << 20;

std::string read_text(const std::string& path, const std::string& what) {
  if (!is_input_file(path, what)) throw InputError(fmt::format("{} '{}' not found", what, path));
  std::error_code ec;
  if (fs::file_size(path, ec) > kMaxDeckBytes) {
    throw InputError(fmt::format("{} '{}' is larger than {} MiB", what, path, kMaxDeckBytes >> 20));
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(fmt::format("{} '{}' cannot be read", what, path));
  return text.str();
}

std::uint64_t fnv1a(const std::string& text, std::uint64_t h) {
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

// SPICE lines with their '+' continuations joined and comments dropped, as ngspice reads them.
std::vector<std::string> logical_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos && line[line.find_first_not_of(" \t")] == '*') continue;
    for (const char* marker : {"$ ", ";"}) {
      const auto comment = line.find(marker);
      if (comment != std::string::npos) line.erase(comment);
    }
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    if (line[first] == '+' && !lines.empty()) {
      lines.back() += " " + line.substr(first + 1);
    } else {
      lines.push_back(line.substr(first));
    }
  }
  return lines;
}

std::vector<std::string> tokens(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string t;
  while (in >> t) out.push_back(t);
  return out;
}

// The .include'd files of a deck, resolved against its folder as ngspice does.
std::vector<std::string> includes(const std::vector<std::string>& lines, const fs::path& folder) {
  std::vector<std::string> out;
  for (const std::string& line : lines) {
    const std::vector<std::string> t = tokens(line);
    if (t.size() < 2 || (ascii_lower(t[0]) != ".include" && ascii_lower(t[0]) != ".inc" && ascii_lower(t[0]) != ".lib")) continue;
    std::string name = t[1];
    if (name.size() >= 2 && (name.front() == '"' || name.front() == '\'')) name = name.substr(1, name.size() - 2);
    const fs::path p = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
    out.push_back(p.string());
  }
  return out;
}

struct Subcircuit {
  std::vector<std::string> ports, params;
  std::vector<std::string> body;
};

std::optional<Subcircuit> find_subckt(const std::vector<std::string>& lines, const std::string& name) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::vector<std::string> t = tokens(lines[i]);
    if (t.size() < 2 || ascii_lower(t[0]) != ".subckt" || ascii_lower(t[1]) != ascii_lower(name)) continue;
    Subcircuit s;
    bool in_params = false;
    for (std::size_t k = 2; k < t.size(); ++k) {
      const std::string word = ascii_lower(t[k]);
      if (word == "params:") {
        in_params = true;
      } else if (in_params || word.find('=') != std::string::npos) {
        in_params = true;
        s.params.push_back(word.substr(0, word.find('=')));
      } else {
        s.ports.push_back(t[k]);
      }
    }
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      const std::vector<std::string> words = tokens(lines[j]);
      if (!words.empty() && ascii_lower(words.front()) == ".ends") break;
      s.body.push_back(lines[j]);
    }
    return s;
  }
  return std::nullopt;
}

}  // namespace

PixelDeck read_pixel_deck(const std::string& path, const std::string& subckt, const std::string& probe_node) {
  PixelDeck deck;
  const std::string text = read_text(path, "deck");
  std::error_code ec;
  deck.path = fs::absolute(path, ec).lexically_normal().string();
  // The path goes into the testbench as `.include "PATH"`, and ngspice's reader cuts that line at
  // a ';' or a " $" (its comment marks) and has no escape for a quote: measured on ngspice 39.
  const bool control = std::any_of(deck.path.begin(), deck.path.end(),
                                   [](char c) { return c == '"' || static_cast<unsigned char>(c) < 0x20; });
  if (control || deck.path.find(';') != std::string::npos || deck.path.find(" $") != std::string::npos) {
    throw InputError(fmt::format("deck '{}': its path has a quote, ';', ' $' or a control character, which ngspice's "
                                 ".include cannot carry; rename or move the deck",
                                 path));
  }
  deck.subckt = subckt;
  deck.given = path;
  std::uint64_t h = fnv1a(text, 0xcbf29ce484222325ull);
  const std::vector<std::string> lines = logical_lines(text);
  std::optional<Subcircuit> found = find_subckt(lines, subckt);
  for (const std::string& inc : includes(lines, fs::path(deck.path).parent_path())) {
    if (!is_input_file(inc, "included file")) continue;  // ngspice names it on the first run
    const std::string included = read_text(inc, "included file");
    h = fnv1a(included, h);
    if (!found) found = find_subckt(logical_lines(included), subckt);
  }
  deck.hash = fmt::format("{:016x}", h);
  if (!found) {
    throw InputError(fmt::format("deck '{}': no subcircuit '{}' (in the deck or the files it includes)", path, subckt));
  }
  if (found->ports.size() != 3) {
    throw InputError(fmt::format("deck '{}': subcircuit '{}' has {} ports; aesim calibrate needs three: vdd out gnd",
                                 path, subckt, found->ports.size()));
  }
  if (std::find(found->params.begin(), found->params.end(), "iph") == found->params.end()) {
    throw InputError(fmt::format("deck '{}': subcircuit '{}' has no parameter iph (params: iph=1p)", path, subckt));
  }
  deck.mc_parameter = std::find(found->params.begin(), found->params.end(), "mc") != found->params.end();
  if (!probe_node.empty()) {
    for (const std::string& line : found->body) {
      const std::vector<std::string> t = tokens(line);
      if (t.empty() || t[0][0] == '.') continue;
      if (std::any_of(t.begin() + 1, t.end(), [&](const std::string& w) { return ascii_lower(w) == ascii_lower(probe_node); })) {
        deck.probe = probe_node;
        break;
      }
    }
  }
  return deck;
}

}  // namespace aesim
