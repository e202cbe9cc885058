#include "aesim/event_files/truth_csv.hpp"

#include <iterator>
#include <ostream>
#include <string>

#include <fmt/format.h>

namespace aesim {

void write_truth_csv(std::ostream& out, const std::vector<TruthRecord>& truth) {
  TruthCsvWriter writer(out);
  writer.truth(truth.data(), truth.size());
}

TruthCsvWriter::TruthCsvWriter(std::ostream& out) : out_(out), buffer_("x,y,tile,t_fire_us,fate,t_deliver_us,latency_us\n") {}

TruthCsvWriter::~TruthCsvWriter() { flush(); }

void TruthCsvWriter::truth(const TruthRecord* first, std::size_t count) {
  for (const TruthRecord* r = first; r != first + count; ++r) {
    const AddressEvent& f = r->firing;
    if (r->fate == Fate::Delivered) {
      fmt::format_to(std::back_inserter(buffer_), "{},{},{},{:.6f},{},{:.6f},{:.6f}\n", f.x, f.y, f.tile, f.t * 1e6,
                     to_string(r->fate), r->t_deliver * 1e6, (r->t_deliver - f.t) * 1e6);
    } else {
      fmt::format_to(std::back_inserter(buffer_), "{},{},{},{:.6f},{},,\n", f.x, f.y, f.tile, f.t * 1e6,
                     to_string(r->fate));
    }
    if (buffer_.size() > (1u << 16)) flush();
  }
}

void TruthCsvWriter::flush() {
  out_ << buffer_;
  buffer_.clear();
}

}  // namespace aesim
