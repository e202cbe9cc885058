#pragma once
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace aesim {

// Records value changes of bus signals within a time window and writes them as a VCD file
// (IEEE 1364 value change dump, 1 ps timescale) that GTKWave opens. SystemC's own tracing cannot
// be limited to a window, and a long run's full trace would be huge.
class VcdRecorder {
 public:
  VcdRecorder(double from_s, double to_s);

  int add_signal(const std::string& scope, const std::string& name, int width);
  // Signals must be reported in non-decreasing time, as a simulation produces them.
  void change(std::uint64_t time_ps, int id, std::uint64_t value);
  void write(std::ostream& out) const;

 private:
  struct Signal {
    std::string scope, name, code;
    int width;
    std::uint64_t initial = 0;  // value at the window start
  };
  struct Change {
    std::uint64_t time_ps;
    int id;
    std::uint64_t value;
  };
  std::string format(const Signal& s, std::uint64_t value) const;

  std::uint64_t from_ps_, to_ps_;
  std::vector<Signal> signals_;
  std::vector<Change> changes_;
};

}  // namespace aesim
