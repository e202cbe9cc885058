#include "aesim/event_files/npy_columns.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/npy_header.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {

NpyNumbers read_npy_numbers(const std::string& npy, const std::string& what, std::uint64_t column, std::uint64_t columns) {
  const NpyHeader h = parse_npy_header(npy, what);
  const std::string& d = h.descr;
  const auto fail = [&](const std::string& why) { return InputError(fmt::format("{}: {}", what, why)); };
  if (d.size() != 3 || (d[0] != '<' && d[0] != '>' && d[0] != '|') || std::string("iufb").find(d[1]) == std::string::npos ||
      d[2] < '1' || d[2] > '8') {
    throw fail(fmt::format("its dtype '{}' is not one of integers, floats or bools", d));
  }
  const int bytes = d[2] - '0';
  if ((d[1] == 'f' && bytes != 4 && bytes != 8) || (d[1] != 'f' && bytes != 1 && bytes != 2 && bytes != 4 && bytes != 8)) {
    throw fail(fmt::format("its dtype '{}' is not one aesim reads", d));
  }
  const std::uint64_t n = h.shape.empty() ? 1 : h.shape[0];
  if (columns == 1 && (h.shape.size() > 2 || (h.shape.size() == 2 && h.shape[1] != 1))) {
    throw fail("it is not one number an event (N or N x 1)");
  }
  if (columns > 1 && (h.shape.size() != 2 || h.shape[1] != columns)) throw fail(fmt::format("it is not N x {}", columns));
  // Before any memory is taken for them: a file of small numbers holds many.
  if (n > kMaxExpandedEvents) throw fail(fmt::format("more than the {} events aesim reads from one file", kMaxExpandedEvents));
  if (n > (npy.size() - h.data_offset) / static_cast<std::uint64_t>(bytes) / columns) {
    throw fail(fmt::format("truncated: {} x {} numbers announced", n, columns));
  }
  NpyNumbers out;
  out.floating = d[1] == 'f';
  out.values.resize(n);
  // Row by row (C order), or column by column (Fortran order).
  const std::uint64_t first = h.fortran_order ? column * n : column, step = h.fortran_order ? 1 : columns;
  for (std::uint64_t i = 0; i < n; ++i) {
    unsigned char b[8];
    std::memcpy(b, npy.data() + h.data_offset + (first + i * step) * static_cast<std::uint64_t>(bytes), static_cast<std::size_t>(bytes));
    if (d[0] == '>') std::reverse(b, b + bytes);
    double v = 0;
    if (d[1] == 'f') {
      if (bytes == 4) {
        float f;
        std::memcpy(&f, b, 4);
        v = f;
      } else {
        std::memcpy(&v, b, 8);
      }
    } else {
      std::uint64_t raw = 0;
      std::memcpy(&raw, b, static_cast<std::size_t>(bytes));
      if (d[1] == 'i' && bytes < 8) {
        const std::uint64_t sign = std::uint64_t(1) << (8 * bytes - 1);
        raw = (raw ^ sign) - sign;
      }
      v = d[1] == 'u' ? static_cast<double>(raw) : static_cast<double>(static_cast<std::int64_t>(raw));
    }
    out.values[i] = v;
  }
  return out;
}

PolarityRecording events_from_columns(const NpyNumbers& xs, const NpyNumbers& ys, const NpyNumbers& ts, const NpyNumbers& ps,
                                      bool seconds, const std::array<std::string, 4>& names, const std::string& label) {
  const std::size_t n = xs.values.size();
  if (ys.values.size() != n || ts.values.size() != n || ps.values.size() != n) {
    throw InputError(fmt::format("event file '{}': the arrays {}, {}, {} and {} hold {}, {}, {} and {} numbers", label, names[0],
                                 names[1], names[2], names[3], n, ys.values.size(), ts.values.size(), ps.values.size()));
  }
  if (n > kMaxExpandedEvents) throw InputError(fmt::format("event file '{}': more than the {} events aesim reads", label, kMaxExpandedEvents));
  PolarityRecording rec;
  rec.events.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = xs.values[i], yi = ys.values[i];
    if (!(xi >= 0 && yi >= 0 && xi < 4096 && yi < 4096) || xi != std::floor(xi) || yi != std::floor(yi)) {
      throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is not a pixel of a 4096x4096 array", label, i, xi, yi));
    }
    const double us = seconds ? std::round(ts.values[i] * 1e6) : ts.values[i];
    if (!(us >= 0 && us < 9e18)) throw InputError(fmt::format("event file '{}': event {} has the stamp {}", label, i, ts.values[i]));
    rec.events[i] = {static_cast<std::int64_t>(us), static_cast<std::int32_t>(xi), static_cast<std::int32_t>(yi), ps.values[i] > 0};
  }
  return rec;
}

}  // namespace aesim
