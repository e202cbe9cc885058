#include "event_files/truth_csv.hpp"

#include <iterator>
#include <ostream>
#include <string>

#include <fmt/format.h>

namespace aesim {

void write_truth_csv(std::ostream& out, const std::vector<TruthRecord>& truth) {
  std::string buffer = "x,y,tile,t_fire_us,fate,t_deliver_us,latency_us\n";
  for (const TruthRecord& r : truth) {
    const AddressEvent& f = r.firing;
    if (r.fate == Fate::Delivered) {
      fmt::format_to(std::back_inserter(buffer), "{},{},{},{:.6f},{},{:.6f},{:.6f}\n", f.x, f.y, f.tile, f.t * 1e6,
                     to_string(r.fate), r.t_deliver * 1e6, (r.t_deliver - f.t) * 1e6);
    } else {
      fmt::format_to(std::back_inserter(buffer), "{},{},{},{:.6f},{},,\n", f.x, f.y, f.tile, f.t * 1e6,
                     to_string(r.fate));
    }
    if (buffer.size() > (1u << 20)) {
      out << buffer;
      buffer.clear();
    }
  }
  out << buffer;
}

}  // namespace aesim
