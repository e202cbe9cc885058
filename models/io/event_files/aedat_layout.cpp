#include "aesim/event_files/aedat_layout.hpp"

#include <cctype>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"

namespace aesim {
namespace {

constexpr JaerChip kDvs128{"ch.unizh.ini.jaer.chip.retina.DVS128", 128, 128};
constexpr JaerChip kDavis240{"eu.seebetter.ini.chips.davis.DAVIS240C", 240, 180};
constexpr JaerChip kDavis346{"eu.seebetter.ini.chips.davis.Davis346red", 346, 260};

bool fits(const AddressMap& map, const JaerChip& chip) { return map.cols() <= chip.width && map.rows() <= chip.height; }

}  // namespace

AedatLayout parse_aedat_layout(const std::string& name) {
  if (name == "aesim") return AedatLayout::Aesim;
  if (name == "dvs128") return AedatLayout::Dvs128;
  if (name == "davis") return AedatLayout::Davis;
  throw InputError(fmt::format("--aedat-layout '{}': use aesim, dvs128 or davis", name));
}

const char* to_string(AedatLayout layout) {
  switch (layout) {
    case AedatLayout::Aesim: return "aesim";
    case AedatLayout::Dvs128: return "dvs128";
    case AedatLayout::Davis: return "davis";
  }
  return "?";
}

JaerChip jaer_chip(AedatLayout layout, const AddressMap& map) {
  if (layout == AedatLayout::Dvs128) {
    if (!fits(map, kDvs128)) {
      throw InputError(fmt::format("--aedat-layout dvs128: the {}x{} array does not fit the DVS128's 128x128 "
                                   "(use davis, or aesim)", map.cols(), map.rows()));
    }
    return kDvs128;
  }
  if (layout == AedatLayout::Davis) {
    if (fits(map, kDavis240)) return kDavis240;
    if (fits(map, kDavis346)) return kDavis346;
    throw InputError(fmt::format("--aedat-layout davis: the {}x{} array does not fit a DAVIS346's 346x260 "
                                 "(use aesim)", map.cols(), map.rows()));
  }
  return {};
}

std::optional<JaerRecordingChip> jaer_recording_chip(const std::string& name) {
  std::string n;
  for (char c : name) n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (n.find("dvs128") != std::string::npos) return JaerRecordingChip{AedatLayout::Dvs128, kDvs128};
  if (n.find("davis240") != std::string::npos) return JaerRecordingChip{AedatLayout::Davis, kDavis240};
  if (n.find("davis346") != std::string::npos) return JaerRecordingChip{AedatLayout::Davis, kDavis346};
  return std::nullopt;
}

std::uint32_t jaer_address(AedatLayout layout, const JaerChip& chip, int rows, const AddressEvent& e) {
  const std::uint32_t y = static_cast<std::uint32_t>(rows - 1) - e.y;
  const std::uint32_t raw_x = static_cast<std::uint32_t>(chip.width - 1) - e.x;
  const bool ghost = (e.flags & kGhostEvent) != 0;
  if (layout == AedatLayout::Dvs128) return (y << 8) | (raw_x << 1) | (ghost ? 1u : 0u);
  return (y << 22) | (raw_x << 12) | ((ghost ? 0u : 1u) << 11);
}

std::optional<JaerPixel> decode_jaer_address(AedatLayout layout, const JaerChip& chip, int rows, int cols,
                                             std::uint32_t word) {
  std::uint32_t raw_x = 0, y = 0;
  bool on = false;
  if (layout == AedatLayout::Dvs128) {
    if (word >> 15) return std::nullopt;
    raw_x = (word & 0xFEu) >> 1;
    y = (word & 0x7F00u) >> 8;
    on = (word & 1u) == 0;
  } else {
    if ((word >> 31) || (word & (1u << 10))) return std::nullopt;  // APS/IMU or special: not a pixel event
    raw_x = (word >> 12) & 0x3FFu;
    y = (word >> 22) & 0x1FFu;
    on = (word >> 11) & 1u;
  }
  const long long x = static_cast<long long>(chip.width - 1) - raw_x;
  if (x < 0 || x >= cols || y >= static_cast<std::uint32_t>(rows)) return std::nullopt;
  JaerPixel p;
  p.pixel = {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(rows - 1) - y};
  p.ghost = !on;
  return p;
}

}  // namespace aesim
