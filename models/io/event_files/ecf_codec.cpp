#include "aesim/event_files/ecf_codec.hpp"

#include <array>
#include <cstring>
#include <vector>

#include <fmt/format.h>

#include "aesim/event_files/checked_bytes.hpp"

namespace aesim {
namespace {

[[noreturn]] void refuse_block(const std::string& message) { throw EcfError(message); }

// `count` copies of `v` from `i` on, within the block's `n` events.
template <typename T>
void fill(std::vector<T>& column, std::size_t& i, std::size_t count, T v, std::size_t n, const char* what, const CheckedBytes& b) {
  if (count > n - i) b.fail(fmt::format("{} for {} events past the block's {}", what, i + count, n));
  for (std::size_t k = 0; k < count; ++k) column[i++] = v;
}

}  // namespace

std::size_t decode_ecf_block(const unsigned char* in, std::size_t bytes, unsigned char* out) {
  CheckedBytes b(std::string_view(reinterpret_cast<const char*>(in), bytes), "ECF block", refuse_block);
  const auto head = b.number<std::uint32_t>("its count");
  const std::size_t n = head >> 2;
  const bool all_packed = (head >> 1) & 1, x_and_p_packed = head & 1;
  if (n > kEcfMostEvents) b.fail(fmt::format("the block claims {} events (ECF's blocks hold at most {})", n, kEcfMostEvents));
  std::vector<std::uint64_t> ts(n);
  std::vector<std::uint16_t> ys(n), xs(n);
  std::vector<std::uint8_t> ps(n);

  std::uint64_t t = b.number<std::uint64_t>("its first stamp");
  for (std::size_t i = 0; i < n;) {
    std::uint8_t v = b.peek<std::uint8_t>("its stamps");
    unsigned step = v >> 4, count = v & 0xF;
    if (step != 0xF) {
      b.number<std::uint8_t>("its stamps");
      t += step;
      if (count == 0xF) count = b.number<std::uint16_t>("a stamp's count");
      fill(ts, i, count, t, n, "stamps", b);
      continue;
    }
    // A longer step, a nibble a byte, least significant first, up to the byte that ends it
    // (read again as a step of its own).
    std::uint64_t longer = 0;
    for (unsigned k = 0; step == 0xF; ++k) {
      if (k == 16) b.fail("a step of time of more than 64 bits");
      longer |= std::uint64_t(count) << (4 * k);
      b.number<std::uint8_t>("its stamps");
      v = b.peek<std::uint8_t>("a step of time");
      step = v >> 4;
      count = v & 0xF;
    }
    t += longer;
  }

  if (all_packed) {
    for (std::size_t i = 0; i < n; i += 4) {
      const std::uint32_t w0 = b.number<std::uint32_t>("packed events"), w1 = b.number<std::uint32_t>("packed events"),
                          w2 = b.number<std::uint32_t>("packed events");
      const std::array<std::uint32_t, 4> v = {w0 >> 8, (w0 & 0xFF) | ((w1 >> 16) << 8), (w1 & 0xFFFF) | ((w2 >> 24) << 16),
                                              w2 & 0xFFFFFF};
      for (std::size_t k = 0; k < 4 && i + k < n; ++k) {
        ys[i + k] = static_cast<std::uint16_t>((v[k] >> 12) & 0x7FF);
        xs[i + k] = static_cast<std::uint16_t>((v[k] >> 1) & 0x7FF);
        ps[i + k] = static_cast<std::uint8_t>(v[k] & 1);
      }
    }
  } else {
    for (std::size_t i = 0; i < n;) {
      const auto w = b.number<std::uint16_t>("its rows");
      std::size_t count = w & 0x1F;
      if (count == 0x1F) count = b.number<std::uint16_t>("a row's count");
      fill(ys, i, count, static_cast<std::uint16_t>(w >> 5), n, "rows", b);
    }
    if (x_and_p_packed) {
      for (std::size_t i = 0; i < n; i += 4) {
        const std::uint16_t w0 = b.number<std::uint16_t>("packed columns"), w1 = b.number<std::uint16_t>("packed columns"),
                            w2 = b.number<std::uint16_t>("packed columns");
        const std::array<unsigned, 4> v = {static_cast<unsigned>(w0 >> 4), (w0 & 0xFu) | ((w1 >> 8u) << 4),
                                           (w1 & 0xFFu) | ((w2 >> 12u) << 8), w2 & 0xFFFu};
        for (std::size_t k = 0; k < 4 && i + k < n; ++k) {
          xs[i + k] = static_cast<std::uint16_t>(v[k] >> 1);
          ps[i + k] = static_cast<std::uint8_t>(v[k] & 1);
        }
      }
    } else {
      for (std::size_t i = 0; i < n;) {
        const auto w = b.number<std::uint16_t>("its columns");
        const auto x = static_cast<std::uint16_t>(w >> 5);
        xs[i++] = x;
        for (unsigned k = 0; k < 5; ++k) {
          if ((w & (1u << (4 - k))) == 0) continue;
          if (i == n) b.fail(fmt::format("columns for more than the block's {} events", n));
          xs[i++] = static_cast<std::uint16_t>(x + k + 1);
        }
      }
      for (std::size_t i = 0; i < n;) {
        const auto v = b.number<std::uint8_t>("its polarities");
        std::size_t count = v & 0x7F;
        if (count == 0x7F) count = b.number<std::uint16_t>("a polarity's count");
        fill(ps, i, count, static_cast<std::uint8_t>(v >> 7), n, "polarities", b);
      }
    }
  }

  for (std::size_t i = 0; i < n; ++i) {
    unsigned char* e = out + i * kEcfEventBytes;
    const std::int16_t p = ps[i];
    const auto stamp = static_cast<std::int64_t>(ts[i]);
    std::memset(e, 0, kEcfEventBytes);
    std::memcpy(e, &xs[i], 2);
    std::memcpy(e + 2, &ys[i], 2);
    std::memcpy(e + 4, &p, 2);
    std::memcpy(e + 8, &stamp, 8);
  }
  return n * kEcfEventBytes;
}

}  // namespace aesim
