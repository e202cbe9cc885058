#pragma once
#include <cstdint>

// The register map of aesim::EventFifoTarget, shared by the model, its tests and a project's
// firmware model. Every register is one 32-bit little-endian word at a word-aligned offset; an
// access is a whole word (length 4, no byte enables, streaming width 4). Reading EVENT pops the
// oldest event and latches its stamp into STAMP; debug reads (transport_dbg) never pop.
namespace aesim::event_fifo {

inline constexpr std::uint32_t kStatus = 0x00;        // RO: the bits below
inline constexpr std::uint32_t kEvent = 0x04;         // RO: pops the oldest event (kEmptyEvent when empty)
inline constexpr std::uint32_t kStamp = 0x08;         // RO: the popped event's stamp, in ticks (low 32 bits)
inline constexpr std::uint32_t kFill = 0x0C;          // RO: events held
inline constexpr std::uint32_t kIrqEnable = 0x10;     // RW: bit 0 enables the interrupt
inline constexpr std::uint32_t kIrqThreshold = 0x14;  // RW: irq while enabled and fill >= threshold (>= 1)
inline constexpr std::uint32_t kOverflows = 0x18;     // RO: events lost to a full FIFO since the last clear
inline constexpr std::uint32_t kControl = 0x1C;       // WO: write kClear to empty the FIFO and zero kOverflows
inline constexpr std::uint32_t kDepth = 0x20;         // RO: the FIFO's capacity in events
inline constexpr std::uint32_t kMapBytes = 0x24;      // the map's extent: offsets from here on are errors

// kStatus bits.
inline constexpr std::uint32_t kNotEmpty = 1u << 0;
inline constexpr std::uint32_t kFull = 1u << 1;
inline constexpr std::uint32_t kIrqPending = 1u << 2;
inline constexpr std::uint32_t kOverflowed = 1u << 3;  // sticky until kClear

// kControl.
inline constexpr std::uint32_t kClear = 1u << 0;

// kEvent: x in bits 0-11, y in 12-23, tile in 24-29, bit 31 set for a ghost (a collision's
// corrupted address); all ones when the FIFO is empty.
inline constexpr std::uint32_t kEmptyEvent = 0xFFFFFFFFu;
inline constexpr std::uint32_t event_word(std::uint32_t x, std::uint32_t y, std::uint32_t tile, bool ghost) {
  return (x & 0xFFFu) | ((y & 0xFFFu) << 12) | ((tile & 0x3Fu) << 24) | (ghost ? 1u << 31 : 0u);
}
inline constexpr std::uint32_t event_x(std::uint32_t word) { return word & 0xFFFu; }
inline constexpr std::uint32_t event_y(std::uint32_t word) { return (word >> 12) & 0xFFFu; }
inline constexpr std::uint32_t event_tile(std::uint32_t word) { return (word >> 24) & 0x3Fu; }
inline constexpr bool event_ghost(std::uint32_t word) { return (word >> 31) != 0; }

}  // namespace aesim::event_fifo
