#include "aesim/array/address_map.hpp"

namespace aesim {

int address_bits_for(int n) {
  int bits = 0;
  while ((1LL << bits) < n) ++bits;
  return bits;
}

AddressMap::AddressMap(const ArrayParams& a)
    : rows_(a.rows),
      cols_(a.cols),
      tile_rows_(a.tile_rows),
      tile_cols_(a.tile_cols),
      tiles_per_row_((a.cols + a.tile_cols - 1) / a.tile_cols),
      tiles_per_col_((a.rows + a.tile_rows - 1) / a.tile_rows),
      xbits_(address_bits_for(a.tile_cols)),
      ybits_(address_bits_for(a.tile_rows)) {}

std::uint32_t AddressMap::tile_of(PixelAddress p) const {
  return (p.y / tile_rows_) * tiles_per_row_ + p.x / tile_cols_;
}

std::uint32_t AddressMap::bus_address(PixelAddress p) const {
  return ((p.y % tile_rows_) << xbits_) | (p.x % tile_cols_);
}

AddressEvent AddressMap::event_at(PixelAddress p) const {
  AddressEvent e;
  e.x = p.x;
  e.y = p.y;
  e.tile = tile_of(p);
  e.bus_address = bus_address(p);
  return e;
}

PixelAddress AddressMap::locate(std::uint32_t tile, std::uint32_t bus_address) const {
  return {(tile % tiles_per_row_) * tile_cols_ + (bus_address & ((1u << xbits_) - 1u)),
          (tile / tiles_per_row_) * tile_rows_ + (bus_address >> xbits_)};
}

std::optional<PixelAddress> AddressMap::decode(std::uint32_t word) const {
  const std::uint32_t tile = word >> bus_bits();
  const std::uint32_t local = word & ((1u << bus_bits()) - 1u);
  const std::uint32_t xl = local & ((1u << xbits_) - 1u);
  const std::uint32_t yl = local >> xbits_;
  if (tile >= static_cast<std::uint32_t>(tiles()) || xl >= static_cast<std::uint32_t>(tile_cols_) ||
      yl >= static_cast<std::uint32_t>(tile_rows_)) {
    return std::nullopt;
  }
  const PixelAddress p = locate(tile, local);
  if (p.x >= static_cast<std::uint32_t>(cols_) || p.y >= static_cast<std::uint32_t>(rows_)) return std::nullopt;
  return p;
}

}  // namespace aesim
