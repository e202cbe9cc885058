#include "aesim/waveform/vcd_recorder.hpp"

#include <cmath>
#include <map>
#include <ostream>

namespace aesim {

VcdRecorder::VcdRecorder(double from_s, double to_s)
    : from_ps_(static_cast<std::uint64_t>(std::llround(from_s * 1e12))),
      to_ps_(static_cast<std::uint64_t>(std::llround(to_s * 1e12))) {}

int VcdRecorder::add_signal(const std::string& scope, const std::string& name, int width) {
  // Identifier codes are printable ASCII from '!' in base 94.
  std::string code;
  for (std::size_t n = signals_.size();; n /= 94) {
    code += static_cast<char>('!' + n % 94);
    if (n < 94) break;
  }
  signals_.push_back({scope, name, code, width});
  return static_cast<int>(signals_.size() - 1);
}

void VcdRecorder::change(std::uint64_t time_ps, int id, std::uint64_t value) {
  if (time_ps < from_ps_) {
    signals_[static_cast<std::size_t>(id)].initial = value;
  } else if (time_ps <= to_ps_) {
    changes_.push_back({time_ps, id, value});
  }
}

std::string VcdRecorder::format(const Signal& s, std::uint64_t value) const {
  if (s.width == 1) return std::string(value ? "1" : "0") + s.code;
  std::string bits = "b";
  for (int b = s.width - 1; b >= 0; --b) bits += ((value >> b) & 1u) ? '1' : '0';
  return bits + " " + s.code;
}

void VcdRecorder::write(std::ostream& out) const {
  out << "$comment aesim bus signals $end\n$timescale 1ps $end\n";
  std::map<std::string, std::vector<const Signal*>> scopes;
  for (const Signal& s : signals_) scopes[s.scope].push_back(&s);
  for (const auto& [scope, list] : scopes) {
    out << "$scope module " << scope << " $end\n";
    for (const Signal* s : list) out << "$var wire " << s->width << ' ' << s->code << ' ' << s->name << " $end\n";
    out << "$upscope $end\n";
  }
  out << "$enddefinitions $end\n#" << from_ps_ << "\n$dumpvars\n";
  for (const Signal& s : signals_) out << format(s, s.initial) << '\n';
  out << "$end\n";
  std::uint64_t current = from_ps_;
  for (const Change& c : changes_) {
    if (c.time_ps != current) {
      out << '#' << c.time_ps << '\n';
      current = c.time_ps;
    }
    out << format(signals_[static_cast<std::size_t>(c.id)], c.value) << '\n';
  }
  out << '#' << to_ps_ << '\n';
}

}  // namespace aesim
