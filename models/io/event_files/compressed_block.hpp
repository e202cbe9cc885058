#pragma once
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace aesim {

// How a container compressed a block of its records whole: ROS 1 bags' chunks (bz2, lz4) and
// MCAP's (lz4, zstd).
enum class BlockCompression { Bz2, Lz4Frame, Zstd };

// The compression a container names "bz2", "lz4" (frames) or "zstd"; nullopt for any other name.
std::optional<BlockCompression> block_compression_named(std::string_view name);

// Why a block did not uncompress to the size its container states.
struct BlockError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `data` uncompressed, which must come to exactly `size` bytes (the container states it, and the
// caller has bounded it); throws BlockError otherwise, or for bytes past the compressed stream,
// saying what the block is as `noun` does ("chunk").
std::string uncompressed_block(BlockCompression compression, std::string_view data, std::size_t size, const char* noun);

// Whether `data` begins as a zstd frame does (its magic number).
bool is_zstd_frame(std::string_view data);
// A zstd frame (or frames) that states its content's size, as ZSTD_compress writes one,
// uncompressed; a size over `most` bytes, or none stated, throws BlockError naming `noun`.
std::string uncompressed_zstd(std::string_view data, std::uint64_t most, const char* noun);

}  // namespace aesim
