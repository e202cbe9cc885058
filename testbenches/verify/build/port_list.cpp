#include "build/port_list.hpp"

#include <cstdlib>
#include <regex>
#include <sstream>

namespace aesim {
namespace {

void set_range(RtlPort& p, int msb, int lsb) {
  p.msb = msb;
  p.lsb = lsb;
  p.width = std::abs(msb - lsb) + 1;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string verilog_name_of(const std::string& member) {
  static const std::string kKeyword = "__SYM__";
  std::string name;
  std::size_t i = member.compare(0, kKeyword.size(), kKeyword) == 0 ? kKeyword.size() : 0;
  while (i < member.size()) {
    if (member.compare(i, 3, "__0") == 0 && i + 4 < member.size() && hex_digit(member[i + 3]) >= 0 &&
        hex_digit(member[i + 4]) >= 0) {
      name += static_cast<char>(16 * hex_digit(member[i + 3]) + hex_digit(member[i + 4]));
      i += 5;
    } else {
      name += member[i++];
    }
  }
  return name;
}

std::vector<RtlPort> ports_in_verilated_header(const std::string& header_text) {
  // VL_IN8(&name,msb,lsb) and VL_OUT16, VL_IN (32 bits), VL_OUT64, VL_INW(&name,msb,lsb,words).
  static const std::regex declaration(R"(VL_(IN|OUT|INOUT)(8|16|64|W)?\(&(\w+),(\d+),(\d+)(,\d+)?\);)");
  std::vector<RtlPort> ports;
  for (auto it = std::sregex_iterator(header_text.begin(), header_text.end(), declaration); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    RtlPort p;
    p.member = m[3];
    p.name = verilog_name_of(p.member);
    p.input = m[1] != "OUT";
    set_range(p, std::stoi(m[4]), std::stoi(m[5]));
    const std::string size = m[2];
    p.bytes = size == "8" ? 1 : size == "16" ? 2 : size.empty() ? 4 : size == "64" ? 8 : 0;
    ports.push_back(p);
  }
  return ports;
}

std::string port_list_text(const std::vector<RtlPort>& ports) {
  std::ostringstream out;
  for (const RtlPort& p : ports) {
    out << (p.input ? "in " : "out ") << p.msb << ' ' << p.lsb << ' ' << p.bytes << ' ' << p.member << '\n';
  }
  return out.str();
}

std::vector<RtlPort> parse_port_list_text(const std::string& text) {
  std::vector<RtlPort> ports;
  std::istringstream in(text);
  std::string direction;
  int msb = 0, lsb = 0;
  RtlPort p;
  while (in >> direction >> msb >> lsb >> p.bytes >> p.member) {
    p.name = verilog_name_of(p.member);
    p.input = direction == "in";
    set_range(p, msb, lsb);
    ports.push_back(p);
  }
  return ports;
}

const RtlPort* find_port(const std::vector<RtlPort>& ports, const std::string& name) {
  for (const RtlPort& p : ports) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

}  // namespace aesim
