#pragma once
#include <cstdint>
#include <optional>

#include "aesim/config/sensor_config.hpp"
#include "aesim/events/address_event.hpp"

namespace aesim {

struct PixelAddress {
  std::uint32_t x = 0, y = 0;  // global, (0, 0) top-left
};

// docs/reference.md section 2: tiles row-major from the top-left, bus address (y_local << xbits) | x_local,
// AEDAT address (tile << bus_bits) | bus address. Arrays that are not a whole number of tiles
// get narrower tiles on the right and bottom edges, with the same address widths.
class AddressMap {
 public:
  explicit AddressMap(const ArrayParams& array);

  int tiles() const { return tiles_per_row_ * tiles_per_col_; }
  int tiles_per_row() const { return tiles_per_row_; }
  int xbits() const { return xbits_; }
  int ybits() const { return ybits_; }
  int bus_bits() const { return xbits_ + ybits_; }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  int tile_rows() const { return tile_rows_; }
  int tile_cols() const { return tile_cols_; }

  std::uint32_t tile_of(PixelAddress p) const;
  std::uint32_t bus_address(PixelAddress p) const;
  // The event pixel p sends: its coordinates, tile and bus address (time 0, no flags).
  AddressEvent event_at(PixelAddress p) const;
  std::uint32_t word(PixelAddress p) const { return (tile_of(p) << bus_bits()) | bus_address(p); }
  // The pixel a bus address names in a tile, without checking it lies inside the array (a ghost
  // address, the OR of several, may name a column past a narrow edge tile).
  PixelAddress locate(std::uint32_t tile, std::uint32_t bus_address) const;
  // Inverse of word(); empty when the word names no pixel of this array.
  std::optional<PixelAddress> decode(std::uint32_t word) const;
  // decode() for an event whose coordinates are its address located (every event aesim makes):
  // whether its bus address names a pixel of its tile, without decode's division (this runs over
  // every event a file receives).
  bool names_pixel(const AddressEvent& e) const {
    const auto xl = e.bus_address & ((1u << xbits_) - 1u), yl = e.bus_address >> xbits_;
    return xl < static_cast<std::uint32_t>(tile_cols_) && yl < static_cast<std::uint32_t>(tile_rows_) &&
           e.x < static_cast<std::uint32_t>(cols_) && e.y < static_cast<std::uint32_t>(rows_);
  }

 private:
  int rows_, cols_, tile_rows_, tile_cols_;
  int tiles_per_row_, tiles_per_col_;
  int xbits_, ybits_;
};

int address_bits_for(int n);

}  // namespace aesim
