#pragma once
#include <cstdint>
#include <utility>
#include <vector>

namespace aesim {

// The pixel side of one tile's ALOHA bus wires, whatever drives time: `addr` is the wired-OR of
// every driving pixel's address, `req` the OR of their requests, `contention` high while two or
// more drive. A pixel that fires drives at once and holds until it sees Ack rise; one that fires
// while Ack is already high sees it and withdraws, driving nothing. The cycle rung's SystemC bus
// (clocked_aloha_bus) and `aesim verify`'s plain C++ driver both drive their wires from this.
template <class Driver>
class WiredOrLines {
 public:
  // False when Ack is high: the pixel withdraws (absorbed).
  bool join(const Driver& driver, std::uint32_t address, bool ack_high) {
    if (ack_high) return false;
    drivers_.push_back(driver);
    addr_ |= address;
    return true;
  }
  // Ack rose: every pixel driving was seen and lets go. They are swapped into `seen` (whatever it
  // held is dropped), whose storage the lines keep for the next drivers: no allocation a
  // transaction.
  void release(std::vector<Driver>& seen) {
    seen.clear();
    seen.swap(drivers_);
    addr_ = 0;
  }
  bool req() const { return !drivers_.empty(); }
  std::uint32_t addr() const { return addr_; }
  bool contention() const { return drivers_.size() >= 2; }
  const std::vector<Driver>& drivers() const { return drivers_; }

 private:
  std::vector<Driver> drivers_;
  std::uint32_t addr_ = 0;
};

}  // namespace aesim
