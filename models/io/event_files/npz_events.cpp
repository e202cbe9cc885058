#include "aesim/event_files/npz_events.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/checked_bytes.hpp"
#include "aesim/event_files/npy_columns.hpp"
#include "aesim/event_files/npy_events.hpp"
#include "aesim/files/npy_header.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

// One array of the archive, where PKWARE's APPNOTE (4.3.12, 4.5.3) puts it.
struct Member {
  std::string name;  // without ".npy"
  std::uint16_t method = 0, flags = 0;
  std::uint32_t crc = 0;
  std::uint64_t packed = 0, size = 0, local = 0;
};

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralHeader = 0x02014b50, kEnd = 0x06054b50;
constexpr std::uint32_t kZip64End = 0x06064b50, kZip64Locator = 0x07064b50;
constexpr std::uint32_t kUnknown32 = 0xFFFFFFFFu;

class NpzArchive {
 public:
  NpzArchive(const std::string& data, const std::string& label) : data_(data), label_(label) { members_ = directory(); }

  const std::vector<Member>& members() const { return members_; }

  // A member's bytes, uncompressed and checked against its CRC32; or only its first `most` bytes
  // (a .npy header's), unchecked.
  std::string bytes(const Member& m, std::uint64_t most = ~std::uint64_t(0)) const {
    CheckedBytes in(std::string_view(data_).substr(std::min<std::uint64_t>(m.local, data_.size())), label_,
                    fmt::format("{}.npy's local header", m.name), static_cast<std::size_t>(std::min<std::uint64_t>(m.local, data_.size())));
    if (in.number<std::uint32_t>("its signature") != kLocalHeader) in.fail("no local file header where the directory says");
    in.take(22, "its fixed fields");
    const auto name = in.number<std::uint16_t>("its name's length");
    const auto extra = in.number<std::uint16_t>("its extra field's length");
    in.take(name + extra, "its name and extra field");
    const std::string_view packed = in.take(m.packed, "its data");
    const bool whole = most >= m.size;
    std::string out;
    if (m.method == 0) {
      if (m.packed != m.size) in.fail("a stored array whose sizes differ");
      out.assign(packed.substr(0, whole ? packed.size() : most));
    } else {
      out.resize(whole ? m.size : most);
      z_stream z{};
      if (inflateInit2(&z, -MAX_WBITS) != Z_OK) throw std::bad_alloc();
      // zlib counts in 32 bits: large arrays go through a gigabyte at a time.
      constexpr std::size_t kSlice = std::size_t(1) << 30;
      std::size_t in_at = 0, out_at = 0;
      int status = Z_OK;
      while (status == Z_OK && out_at < out.size()) {
        const std::size_t in_n = std::min(packed.size() - in_at, kSlice), out_n = std::min(out.size() - out_at, kSlice);
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data() + in_at));
        z.avail_in = static_cast<uInt>(in_n);
        z.next_out = reinterpret_cast<Bytef*>(out.data() + out_at);
        z.avail_out = static_cast<uInt>(out_n);
        status = inflate(&z, Z_NO_FLUSH);
        const std::size_t used = in_n - z.avail_in, made = out_n - z.avail_out;
        in_at += used;
        out_at += made;
        if (status == Z_BUF_ERROR && (used > 0 || made > 0)) status = Z_OK;
      }
      inflateEnd(&z);
      if (out_at != out.size() || (whole && status != Z_STREAM_END)) {
        in.fail(fmt::format("its deflated data do not inflate to its {} bytes", m.size));
      }
    }
    if (whole) {
      const auto sum = static_cast<std::uint32_t>(crc32_z(crc32_z(0, nullptr, 0), reinterpret_cast<const Bytef*>(out.data()), out.size()));
      if (sum != m.crc) in.fail(fmt::format("its data do not match their CRC32 (0x{:08x}, the archive says 0x{:08x})", sum, m.crc));
    }
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(fmt::format("event file '{}': {}", label_, why));
  }

  // The central directory, found from its end record (and Zip64's, which NumPy writes).
  std::vector<Member> directory() const {
    if (data_.size() < 22) fail("not a .npz archive (too short for a ZIP file's end record)");
    // The end record is the last 22 bytes, or earlier by an archive comment of up to 65535 bytes.
    std::size_t end = std::string::npos;
    for (std::size_t at = data_.size() - 22;; --at) {
      std::uint32_t sig;
      std::memcpy(&sig, data_.data() + at, 4);
      if (sig == kEnd) {
        end = at;
        break;
      }
      if (at == 0 || data_.size() - at > 22 + 65535) break;
    }
    if (end == std::string::npos) {
      if (data_.compare(0, 6, kNpyMagic) == 0) fail("a .npy file named .npz: rename it .npy");
      fail("not a .npz archive (no ZIP end record)");
    }
    CheckedBytes e(std::string_view(data_).substr(end), label_, "the ZIP end record", end);
    e.take(10, "its disk numbers and count on this disk");
    std::uint64_t count = e.number<std::uint16_t>("its count of arrays");
    std::uint64_t size = e.number<std::uint32_t>("its directory's size");
    std::uint64_t offset = e.number<std::uint32_t>("its directory's offset");
    if ((count == 0xFFFF || size == kUnknown32 || offset == kUnknown32) && end >= 20) {
      CheckedBytes locator(std::string_view(data_).substr(end - 20, 20), label_, "the Zip64 end locator", end - 20);
      if (locator.number<std::uint32_t>("its signature") == kZip64Locator) {
        locator.take(4, "its disk");
        const auto at = locator.number<std::uint64_t>("the Zip64 end record's offset");
        CheckedBytes z(std::string_view(data_).substr(std::min<std::uint64_t>(at, data_.size())), label_, "the Zip64 end record",
                       static_cast<std::size_t>(std::min<std::uint64_t>(at, data_.size())));
        if (z.number<std::uint32_t>("its signature") != kZip64End) z.fail("no Zip64 end record where its locator says");
        z.take(8 + 2 + 2 + 4 + 4 + 8, "its sizes, versions and disks");
        count = z.number<std::uint64_t>("its count of arrays");
        size = z.number<std::uint64_t>("its directory's size");
        offset = z.number<std::uint64_t>("its directory's offset");
      }
    }
    if (offset > data_.size() || size > data_.size() - offset) fail("its directory lies past the end of the file");
    CheckedBytes d(std::string_view(data_).substr(offset, size), label_, "the ZIP directory", offset);
    if (count > size / 46) fail(fmt::format("its directory claims {} arrays in {} bytes", count, size));
    std::vector<Member> members;
    for (std::uint64_t k = 0; k < count; ++k) {
      if (d.number<std::uint32_t>("an entry's signature") != kCentralHeader) d.fail("not a directory entry");
      d.take(4, "its versions");
      Member m;
      m.flags = d.number<std::uint16_t>("its flags");
      m.method = d.number<std::uint16_t>("its compression");
      d.take(4, "its time and date");
      m.crc = d.number<std::uint32_t>("its CRC32");
      m.packed = d.number<std::uint32_t>("its compressed size");
      m.size = d.number<std::uint32_t>("its size");
      const auto name = d.number<std::uint16_t>("its name's length");
      const auto extra = d.number<std::uint16_t>("its extra field's length");
      const auto comment = d.number<std::uint16_t>("its comment's length");
      d.take(8, "its disk and attributes");
      m.local = d.number<std::uint32_t>("its local header's offset");
      m.name = std::string(d.take(name, "its name"));
      // Zip64's extra field: the 8-byte sizes and offset the 4-byte fields could not hold, in this order.
      CheckedBytes x(d.take(extra, "its extra field"), label_, fmt::format("{}'s extra field", m.name));
      while (x.left() >= 4) {
        const auto id = x.number<std::uint16_t>("a field's id");
        CheckedBytes f(x.take(x.number<std::uint16_t>("a field's length"), "a field"), label_, fmt::format("{}'s Zip64 field", m.name));
        if (id != 0x0001) continue;
        if (m.size == kUnknown32) m.size = f.number<std::uint64_t>("its size");
        if (m.packed == kUnknown32) m.packed = f.number<std::uint64_t>("its compressed size");
        if (m.local == kUnknown32) m.local = f.number<std::uint64_t>("its local header's offset");
      }
      d.take(comment, "its comment");
      if (m.flags & 1) fail(fmt::format("{} is encrypted", m.name));
      if (m.method != 0 && m.method != 8) fail(fmt::format("{} is compressed with ZIP method {} (NumPy stores or deflates)", m.name, m.method));
      if (m.size > kMaxEventFileBytes) fail(fmt::format("{} claims {} bytes, more than aesim reads from one file", m.name, m.size));
      // Deflate makes at most about 1032 bytes of one: a claim past that is false.
      if (m.method == 8 && m.size / 1032 > m.packed + 1) fail(fmt::format("{} claims {} bytes from {} deflated", m.name, m.size, m.packed));
      if (m.name.size() > 4 && m.name.compare(m.name.size() - 4, 4, ".npy") == 0) {
        m.name.resize(m.name.size() - 4);
        members.push_back(m);
      }
    }
    return members;
  }

  const std::string& data_;
  std::string label_;
  std::vector<Member> members_;
};

const Member* named(const std::vector<Member>& members, std::initializer_list<const char*> names) {
  for (const char* name : names) {
    const auto it = std::find_if(members.begin(), members.end(), [&](const Member& m) { return m.name == name; });
    if (it != members.end()) return &*it;
  }
  return nullptr;
}

}  // namespace

PolarityRecording decode_npz(const std::string& data, const std::string& label) {
  const NpzArchive archive(data, label);
  const std::vector<Member>& members = archive.members();
  // A structured array of events, the first the archive holds.
  // An array's header alone (a .npy header is under 64 kB): arrays are read whole only once
  // chosen, and only if they hold no more events than aesim reads.
  const auto header = [&](const Member& m) {
    return parse_npy_header(archive.bytes(m, 1u << 16), fmt::format("event file '{}' ({}.npy)", label, m.name));
  };
  const auto bounded = [&](const Member& m, const NpyHeader& h) {
    std::uint64_t n = 1;
    for (const std::uint64_t d : h.shape) n = d != 0 && n > kMaxExpandedEvents / d ? kMaxExpandedEvents + 1 : n * d;
    if (n > kMaxExpandedEvents) {
      throw InputError(fmt::format("event file '{}': {} holds more than the {} events aesim reads from one file", label, m.name,
                                   kMaxExpandedEvents));
    }
  };
  for (const Member& m : members) {
    const NpyHeader h = header(m);
    if (h.descr.empty() || h.descr.front() != '[' || h.descr.find("('x'") == std::string::npos) continue;
    bounded(m, h);
    PolarityRecording rec = decode_npy(archive.bytes(m), fmt::format("{} ({}.npy)", label, m.name));
    for (const Member& other : members) {
      if (&other != &m) rec.notes.push_back(fmt::format("the array {} (the events are {}'s)", other.name, m.name));
    }
    put_in_time_order(rec);
    return rec;
  }
  // Or one array a field.
  const Member* x = named(members, {"x"});
  const Member* y = named(members, {"y"});
  const Member* t = named(members, {"t", "ts", "timestamp", "timestamps"});
  const Member* p = named(members, {"p", "polarity", "pol", "polarities"});
  const auto column = [&](const Member* m) {
    bounded(*m, header(*m));
    return read_npy_numbers(archive.bytes(*m), fmt::format("event file '{}' ({}.npy)", label, m->name));
  };
  // EVIMO's archive (EVIMO and EVIMO2v1, as its ground-truth-format page lays it out): `events`,
  // N x 4, each row an event's stamp in seconds, x, y and polarity, beside its lookup table of the
  // events every `discretization` seconds (`index`), which tells the archive apart from an N x 4
  // array whose columns nobody named (refused below).
  const auto evimo_events = [&]() -> const Member* {
    const Member* e = named(members, {"events"});
    if (e == nullptr || named(members, {"index"}) == nullptr || named(members, {"discretization"}) == nullptr) return nullptr;
    const NpyHeader h = header(*e);
    if (h.shape.size() != 2 || h.shape[1] != 4) return nullptr;
    if (h.shape[0] > kMaxExpandedEvents) {
      throw InputError(fmt::format("event file '{}': events holds more than the {} events aesim reads from one file", label,
                                   kMaxExpandedEvents));
    }
    return e;
  };
  NpyNumbers xs, ys, ts, ps;
  std::array<std::string, 4> names;  // x, y, t, p's, for messages
  std::array<const Member*, 4> used{};  // the arrays read; the rest null
  bool seconds = false;
  std::string layout;
  if (x != nullptr && y != nullptr && t != nullptr && p != nullptr) {
    xs = column(x), ys = column(y), ts = column(t), ps = column(p);
    names[0] = x->name, names[1] = y->name, names[2] = t->name, names[3] = p->name;
    used = {x, y, t, p};
    // Whole stamps are microseconds; a stamp with a fraction makes them all seconds.
    seconds = ts.floating && std::any_of(ts.values.begin(), ts.values.end(), [](double v) { return v != std::floor(v); });
    layout = fmt::format("the arrays {}, {}, {}, {} (stamps in {}, ON where the polarity is above 0)", x->name, y->name, t->name,
                         p->name, seconds ? "seconds: they have fractions" : "microseconds");
  } else if (const Member* e = evimo_events(); e != nullptr) {
    const std::string bytes = archive.bytes(*e);
    const std::string what = fmt::format("event file '{}' (events.npy)", label);
    ts = read_npy_numbers(bytes, what, 0, 4), xs = read_npy_numbers(bytes, what, 1, 4), ys = read_npy_numbers(bytes, what, 2, 4),
    ps = read_npy_numbers(bytes, what, 3, 4);
    names[0] = "events[:, 1]", names[1] = "events[:, 2]", names[2] = "events[:, 0]", names[3] = "events[:, 3]";
    used = {e};
    seconds = true;
    layout = "EVIMO's events array, its columns t (seconds), x, y, p (ON where the polarity is above 0; EVIMO2's Samsung "
             "camera's polarity is the other way round)";
  } else {
    std::string held;
    for (const Member& m : members) held += (held.empty() ? "" : ", ") + m.name;
    throw InputError(fmt::format("event file '{}': no events (a structured array of x, y, t, p, arrays x, y, t and p, or EVIMO's "
                                 "events of N x 4 beside its index and discretization; the archive holds {})",
                                 label, held.empty() ? "no arrays" : held));
  }
  PolarityRecording rec = events_from_columns(xs, ys, ts, ps, seconds, names, label);
  rec.read_as.push_back(layout);
  for (const Member& m : members) {
    if (std::find(used.begin(), used.end(), &m) == used.end()) rec.notes.push_back(fmt::format("the array {}", m.name));
  }
  put_in_time_order(rec);
  return rec;
}

}  // namespace aesim
