#pragma once
#include <cstddef>
#include <cstdint>

namespace aesim {

// What aesim handles at most, stated once; the docs/reliability.md lists them. Each is
// checked before memory is taken for it, so a tiny file cannot ask for a huge allocation.
constexpr long long kMaxArrayPixels = 1LL << 24;   // pixels in an array or an image: 4096 x 4096
// Pixels of a photograph (PNG, JPEG, TIFF) decoded row by row and averaged down to at most
// kMaxArrayPixels: a 200 MP phone's, at about 10 ns a pixel.
constexpr long long kMaxDecodedPixels = 1LL << 28;
constexpr int kMaxTiles = 1 << 16;                 // tiles (each has its own bus and receiver)
constexpr std::uintmax_t kMaxInputFileBytes = 1ULL << 28;  // 256 MiB: a scene image or frame
constexpr std::uintmax_t kMaxEventFileBytes = 1ULL << 34;  // 16 GiB: an event file, read whole
// Events decoded from one file whose words expand (a Prophesee EVT 3.0 word holds up to 12) or
// that takes under 8 bytes an event (an N-MNIST record, 5): 13 GB as aesim holds them, where a
// file of the other formats holds each event in 8 bytes or more.
constexpr std::uint64_t kMaxExpandedEvents = 1ULL << 28;
constexpr double kMaxFrameRate = 1e9;              // Hz, of any scene or video
constexpr std::size_t kMaxSceneFrames = 100000;    // frames of a scene folder or a video
// A scene's frames at the array's size, with the photocurrents made of them (16 bytes a pixel a
// frame), estimated before any frame is read.
constexpr double kMaxSceneBytes = 2.0 * (1ULL << 30);

}  // namespace aesim
