#include "aesim/event_files/npy_events.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/files/descriptor_io.hpp"
#include "aesim/files/npy_header.hpp"
#include "aesim/output/temp_files.hpp"
#include "aesim/event_files/event_stamps.hpp"

namespace aesim {
namespace {

constexpr std::size_t kNpyRecordBytes = 13;
constexpr std::size_t kNpyBufferBytes = std::size_t(1) << 20;
// The header of format 1.0 is 10 bytes of preamble and a text padded to a multiple of 64 bytes.
constexpr std::size_t kNpyHeaderBytes = 256;

std::string header_text(std::uint64_t count) {
  // The count is written in a fixed-width field so that finish() can overwrite it in place.
  std::string text = fmt::format(
      "{{'descr': [('x', '<i2'), ('y', '<i2'), ('t', '<i8'), ('p', '|b1')], 'fortran_order': False, "
      "'shape': ({:20d},), }}",
      count);
  static_assert(kNpyHeaderBytes % 64 == 0, "NumPy aligns the data to 64 bytes");
  if (text.size() > kNpyHeaderBytes - 10 - 1) throw std::logic_error(".npy header text too long");
  text.resize(kNpyHeaderBytes - 10 - 1, ' ');
  return text + '\n';
}

struct Field {
  std::size_t offset = 0;
  int bytes = 0;
  bool is_signed = false, is_bool = false, is_float = false, big_endian = false;
};

// The field a role reads, by the names tools give it: tonic's x, y, t, p, and the longer names
// other scripts use.
const Field* role_field(const std::map<std::string, Field>& fields, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    if (const auto it = fields.find(name); it != fields.end()) return &it->second;
  }
  return nullptr;
}

}  // namespace

namespace {

// An empty file (OutputFiles' temporary, made when the writer was given it) is opened as it is:
// opened with O_TRUNC, even empty, ext4 marks it as one being replaced and on close writes all of
// it out to the disk, in the closing thread (auto_da_alloc), where without it the system writes
// it back later on its own. Any other file is truncated as usual.
int open_npy(const std::string& path) {
  std::error_code ec;
  const bool empty = std::filesystem::is_regular_file(path, ec) && std::filesystem::file_size(path, ec) == 0 && !ec;
  return ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (empty ? 0 : O_TRUNC), 0644);
}

}  // namespace

NpyWriter::NpyWriter(const std::string& path, double tick) : fd_(open_npy(path)), path_(path), stamps_(tick) {
  if (fd_ < 0) throw OutputError(write_failure(path));
  const std::string text = header_text(0);
  const char version[4] = {1, 0, static_cast<char>(text.size() & 0xff), static_cast<char>(text.size() >> 8)};
  buffer_.reserve(kNpyBufferBytes + kNpyRecordBytes);  // fit rounds up: one record past the mark at most
  buffer_.resize(kNpyHeaderBytes);
  std::memcpy(buffer_.data(), kNpyMagic, 6);
  std::memcpy(buffer_.data() + 6, version, 4);
  std::memcpy(buffer_.data() + 10, text.data(), text.size());
}

NpyWriter::~NpyWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void NpyWriter::events(const AddressEvent* first, std::size_t count) {
  // A local copy: the records' stores would otherwise make the loop reload the tick's constants.
  const MicrosecondStamps stamps = stamps_;
  for (std::size_t i = 0; i < count;) {
    // As many records as fit before the buffer is due to be written, made room for at once.
    const std::size_t fit = (kNpyBufferBytes - buffer_.size() + kNpyRecordBytes - 1) / kNpyRecordBytes;
    const std::size_t n = std::min(count - i, std::max<std::size_t>(fit, 1));
    const std::size_t at = buffer_.size();
    buffer_.resize(at + n * kNpyRecordBytes);
    char* p = buffer_.data() + at;
    // Fixed-size copies of little-endian values (this machine's order, as the dtype's): a store
    // each, not a byte at a time.
    for (const AddressEvent* e = first + i; e != first + i + n; ++e, p += kNpyRecordBytes) {
      const auto x = static_cast<std::uint16_t>(e->x), y = static_cast<std::uint16_t>(e->y);
      const std::uint64_t t = stamps(e->t);
      std::memcpy(p, &x, 2);
      std::memcpy(p + 2, &y, 2);
      std::memcpy(p + 4, &t, 8);
      p[12] = e->flags == kGhostEvent ? 0 : 1;
    }
    i += n;
    if (buffer_.size() >= kNpyBufferBytes) flush();
  }
  count_ += count;
}

void NpyWriter::write_at(const char* data, std::size_t n, std::uint64_t offset) {
  if (const int error = write_fully_at(fd_, data, n, offset)) {
    errno = error;
    throw OutputError(write_failure(path_));
  }
}

void NpyWriter::flush() {
  space_.before_writing_to(fd_, written_ + buffer_.size());
  write_at(buffer_.data(), buffer_.size(), written_);
  written_ += buffer_.size();
  buffer_.clear();
}

void NpyWriter::finish() {
  flush();
  const std::string text = header_text(count_);
  write_at(text.data(), text.size(), 10);
  space_.release(fd_);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw OutputError(write_failure(path_));
}

PolarityRecording decode_npy(const std::string& data, const std::string& label) {
  const auto fail = [&](const std::string& why) { return InputError(fmt::format("event file '{}': {}", label, why)); };
  const NpyHeader h = parse_npy_header(data, fmt::format("event file '{}'", label));
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  const std::size_t at = h.data_offset;
  if (h.fortran_order) throw fail(".npy array in Fortran order is not supported");
  // The structured dtype: ('name', 'type') pairs in the order they lie in a record.
  const std::string& descr = h.descr;
  if (descr.empty() || descr.front() != '[') throw fail("the .npy dtype is not a structured array of x, y, t, p");
  const std::size_t list_end = descr.size() - 1;
  std::map<std::string, Field> fields;
  std::size_t record = 0;
  for (std::size_t pos = descr.find("('"); pos != std::string::npos && pos < list_end;
       pos = descr.find("('", pos + 1)) {
    const std::size_t name_end = descr.find('\'', pos + 2);
    const std::size_t type_begin = name_end == std::string::npos ? name_end : descr.find('\'', name_end + 1);
    const std::size_t type_end = type_begin == std::string::npos ? type_begin : descr.find('\'', type_begin + 1);
    if (type_end == std::string::npos || type_end > list_end) throw fail("malformed .npy dtype");
    const std::string name = descr.substr(pos + 2, name_end - pos - 2);
    const std::string type = descr.substr(type_begin + 1, type_end - type_begin - 1);
    Field f;
    f.offset = record;
    const char order = type.empty() ? '?' : type[0], kind = type.size() > 1 ? type[1] : '?';
    const int width = type.size() == 3 && type[2] >= '1' && type[2] <= '8' ? type[2] - '0' : 0;
    const bool integer = (kind == 'i' || kind == 'u' || kind == 'b') && width > 0;
    const bool floating = kind == 'f' && (width == 4 || width == 8);
    if ((order != '<' && order != '>' && order != '|') || !(integer || floating) || (order == '|' && width != 1)) {
      throw fail(fmt::format("field '{}' has type '{}': aesim reads integers, bools and 32- or 64-bit floats", name, type));
    }
    f.bytes = width;
    f.is_signed = kind == 'i';
    f.is_bool = kind == 'b';
    f.is_float = floating;
    f.big_endian = order == '>';
    record += static_cast<std::size_t>(f.bytes);
    fields[name] = f;
  }
  const Field* const fx = role_field(fields, {"x"});
  const Field* const fy = role_field(fields, {"y"});
  const Field* const ft = role_field(fields, {"t", "ts", "timestamp", "time"});
  const Field* const fp = role_field(fields, {"p", "pol", "polarity", "on"});
  if (!fx || !fy || !ft) {
    throw fail(fmt::format("the .npy dtype has no field '{}' (tonic's x, y, t, p; the time may be ts, timestamp or time)",
                           !fx ? "x" : !fy ? "y" : "t"));
  }
  if (fx->is_float || fy->is_float || (fp && fp->is_float)) throw fail("x, y and the polarity must be integers or bools");
  if (h.shape.size() != 1) throw fail("the .npy array is not one-dimensional");
  const std::uint64_t n = h.shape.front();
  if (record == 0 || n > (data.size() - at) / record) throw fail(fmt::format("truncated: {} records announced", n));
  PolarityRecording rec;
  rec.events.resize(n);
  const auto raw_of = [](const unsigned char* r, const Field& f) {
    std::uint64_t raw = 0;
    for (int i = 0; i < f.bytes; ++i) {
      const int shift = 8 * (f.big_endian ? f.bytes - 1 - i : i);
      raw |= std::uint64_t(r[f.offset + static_cast<std::size_t>(i)]) << shift;
    }
    return raw;
  };
  const auto value = [&](const unsigned char* r, const Field& f) -> std::int64_t {
    const std::uint64_t raw = raw_of(r, f);
    if (!f.is_signed || f.bytes == 8) return static_cast<std::int64_t>(raw);
    const std::uint64_t sign = std::uint64_t(1) << (8 * f.bytes - 1);
    return static_cast<std::int64_t>((raw ^ sign) - sign);
  };
  const auto real = [&](const unsigned char* r, const Field& f) -> double {
    const std::uint64_t raw = raw_of(r, f);
    if (f.bytes == 4) {
      float v;
      const auto bits = static_cast<std::uint32_t>(raw);
      std::memcpy(&v, &bits, 4);
      return v;
    }
    double v;
    std::memcpy(&v, &raw, 8);
    return v;
  };
  UnnamedStampUnit unnamed;
  for (std::size_t i = 0; i < n && ft->is_float; ++i) {
    const double t = real(bytes + at + i * record, *ft);
    if (!std::isfinite(t) || t < 0 || t > 1e12 * 1e6) throw fail(fmt::format("event {} has time {}: not a time", i, t));
    unnamed.see(t);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char* r = bytes + at + i * record;
    PolarityEvent& e = rec.events[i];
    const std::int64_t x = value(r, *fx), y = value(r, *fy);
    if (x < 0 || y < 0 || x >= 4096 || y >= 4096) throw fail(fmt::format("event {} at ({}, {}) is outside 4096x4096", i, x, y));
    e.x = static_cast<std::int32_t>(x);
    e.y = static_cast<std::int32_t>(y);
    if (ft->is_float) {
      const double t = real(r, *ft);
      if (unnamed.seconds && t > 1e12) throw fail(fmt::format("event {} is stamped {} s, past 1e12 s", i, t));
      e.t_us = unnamed.microseconds(t);
    } else {
      e.t_us = value(r, *ft);
    }
    e.on = !fp || value(r, *fp) > 0;
  }
  if (ft->is_float && n > 0) {
    rec.read_as.push_back(std::string("a float time field in ") + unnamed.words());
  }
  put_in_time_order(rec);
  return rec;
}

}  // namespace aesim
