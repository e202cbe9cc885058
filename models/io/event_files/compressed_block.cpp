#include "aesim/event_files/compressed_block.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <memory>
#include <new>

#include <fmt/format.h>

namespace aesim {
namespace {

void bz2(std::string_view data, std::string& plain, const char* noun) {
  auto out = static_cast<unsigned int>(plain.size());
  // bzlib takes no const input; it does not write to it.
  const int status = BZ2_bzBuffToBuffDecompress(plain.data(), &out, const_cast<char*>(data.data()),
                                                static_cast<unsigned int>(data.size()), 0, 0);
  if (status != BZ_OK || out != plain.size()) {
    throw BlockError(fmt::format("a bz2 {} does not uncompress to its {} bytes (bzlib status {})", noun, plain.size(), status));
  }
}

void lz4_frame(std::string_view data, std::string& plain, const char* noun) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw std::bad_alloc();
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(raw, LZ4F_freeDecompressionContext);
  std::size_t made = 0, used = 0, hint = 1;
  while (hint != 0) {
    std::size_t out = plain.size() - made, consumed = data.size() - used;
    hint = LZ4F_decompress(dctx.get(), plain.data() + made, &out, data.data() + used, &consumed, nullptr);
    if (LZ4F_isError(hint)) throw BlockError(fmt::format("an lz4 {}: LZ4: {}", noun, LZ4F_getErrorName(hint)));
    made += out;
    used += consumed;
    if (hint != 0 && out == 0 && consumed == 0) break;  // no progress: the frame is cut or overflows
  }
  if (hint != 0 || made != plain.size() || used != data.size()) {
    throw BlockError(fmt::format("an lz4 {} does not uncompress to its {} bytes", noun, plain.size()));
  }
}

void zstd(std::string_view data, std::string& plain, const char* noun) {
  // One call for the frames the block holds (a writer may close one frame and start another).
  const std::size_t made = ZSTD_decompress(plain.data(), plain.size(), data.data(), data.size());
  if (ZSTD_isError(made)) throw BlockError(fmt::format("a zstd {}: zstd: {}", noun, ZSTD_getErrorName(made)));
  if (made != plain.size()) throw BlockError(fmt::format("a zstd {} uncompresses to {} bytes, not its {}", noun, made, plain.size()));
}

}  // namespace

std::optional<BlockCompression> block_compression_named(std::string_view name) {
  if (name == "bz2") return BlockCompression::Bz2;
  if (name == "lz4") return BlockCompression::Lz4Frame;
  if (name == "zstd") return BlockCompression::Zstd;
  return std::nullopt;
}

std::string uncompressed_block(BlockCompression compression, std::string_view data, std::size_t size, const char* noun) {
  std::string plain(size, '\0');
  switch (compression) {
    case BlockCompression::Bz2: bz2(data, plain, noun); break;
    case BlockCompression::Lz4Frame: lz4_frame(data, plain, noun); break;
    case BlockCompression::Zstd: zstd(data, plain, noun); break;
  }
  return plain;
}

bool is_zstd_frame(std::string_view data) { return data.size() >= 4 && data.substr(0, 4) == std::string_view("\x28\xb5\x2f\xfd", 4); }

std::string uncompressed_zstd(std::string_view data, std::uint64_t most, const char* noun) {
  const unsigned long long size = ZSTD_getFrameContentSize(data.data(), data.size());
  if (size == ZSTD_CONTENTSIZE_UNKNOWN || size == ZSTD_CONTENTSIZE_ERROR) {
    throw BlockError(fmt::format("a zstd {} that does not state its size", noun));
  }
  if (size > most) throw BlockError(fmt::format("a zstd {} of {} bytes uncompressed, more than aesim reads in one", noun, size));
  return uncompressed_block(BlockCompression::Zstd, data, static_cast<std::size_t>(size), noun);
}

}  // namespace aesim
