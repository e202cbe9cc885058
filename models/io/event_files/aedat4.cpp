#include "aesim/event_files/aedat4.hpp"

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string_view>

#include <flatbuffers/flatbuffers.h>
#include <fmt/format.h>
#include <lz4frame.h>
#include <zstd.h>

#include "FileDataTable_generated.h"
#include "IOHeader_generated.h"
#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/threads/serial_worker.hpp"
#include "events_generated.h"

namespace aesim {
namespace {

constexpr char kAedat4Magic[] = "#!AER-DAT4.0\r\n";
constexpr std::size_t kAedat4MagicBytes = sizeof(kAedat4Magic) - 1;
// DV's recorder writes packets of a few thousand events; so do we (64 KiB of events a packet).
constexpr std::size_t kAedat4PacketEvents = 4096;
// A malformed or hostile file cannot make the reader decompress without end.
constexpr std::uint64_t kAedat4MaxPacketBytes = 1ULL << 28;
constexpr std::uint64_t kAedat4MaxDecodedBytes = 1ULL << 33;

void put_le32(std::ostream& out, std::uint32_t v) {
  const char b[4] = {static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 24)};
  out.write(b, 4);
}

std::uint32_t get_le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24);
}

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string xml_unescape(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    static const std::pair<const char*, char> kEntities[] = {
        {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}, {"&apos;", '\''}};
    bool known = false;
    for (const auto& [name, c] : kEntities) {
      if (s.compare(i, std::strlen(name), name) == 0) {
        out += c;
        i += std::strlen(name) - 1;
        known = true;
        break;
      }
    }
    if (!known) out += '&';
  }
  return out;
}

std::string info_node(const EventFileSpec& spec) {
  const std::string compression = spec.compression == Aedat4Compression::Lz4    ? "LZ4"
                                  : spec.compression == Aedat4Compression::Zstd ? "ZSTD"
                                                                                 : "NONE";
  const std::string path = "/mainloop/aesim/outInfo/0/";
  std::string xml = "<dv version=\"2.0\">\n <node name=\"outInfo\" path=\"/mainloop/aesim/outInfo/\">\n";
  xml += fmt::format("  <node name=\"0\" path=\"{}\">\n", path);
  xml += fmt::format("   <attr key=\"compression\" type=\"string\">{}</attr>\n", compression);
  xml += "   <attr key=\"originalModuleName\" type=\"string\">aesim</attr>\n";
  xml += "   <attr key=\"originalOutputName\" type=\"string\">events</attr>\n";
  xml += "   <attr key=\"typeDescription\" type=\"string\">Array of events (polarity ON/OFF).</attr>\n";
  xml += "   <attr key=\"typeIdentifier\" type=\"string\">EVTS</attr>\n";
  xml += fmt::format("   <node name=\"info\" path=\"{}info/\">\n", path);
  xml += fmt::format("    <attr key=\"sizeX\" type=\"int\">{}</attr>\n", spec.array.cols);
  xml += fmt::format("    <attr key=\"sizeY\" type=\"int\">{}</attr>\n", spec.array.rows);
  xml += "    <attr key=\"source\" type=\"string\">aesim</attr>\n";
  xml += "    <attr key=\"tsOffset\" type=\"long\">0</attr>\n";
  for (const auto& [key, value] : spec.sensor) {
    xml += fmt::format("    <attr key=\"aesim.sensor.{}\" type=\"string\">{}</attr>\n", xml_escape(key),
                       xml_escape(value));
  }
  xml += "   </node>\n  </node>\n </node>\n</dv>\n";
  return xml;
}

// The attributes (key -> text) of the info node's <attr> elements, in document order.
std::vector<std::pair<std::string, std::string>> xml_attrs(const std::string& xml) {
  std::vector<std::pair<std::string, std::string>> out;
  std::size_t pos = 0;
  while ((pos = xml.find("<attr key=\"", pos)) != std::string::npos) {
    const std::size_t key_begin = pos + 11;
    const std::size_t key_end = xml.find('"', key_begin);
    const std::size_t open_end = key_end == std::string::npos ? key_end : xml.find('>', key_end);
    const std::size_t close = open_end == std::string::npos ? open_end : xml.find("</attr>", open_end);
    if (close == std::string::npos) break;
    out.emplace_back(xml_unescape(xml.substr(key_begin, key_end - key_begin)),
                     xml_unescape(xml.substr(open_end + 1, close - open_end - 1)));
    pos = close;
  }
  return out;
}

// One LZ4 frame of `size` bytes into `out`; returns its size.
std::size_t lz4_frame(const char* data, std::size_t size, std::vector<char>& out) {
  LZ4F_preferences_t prefs;
  std::memset(&prefs, 0, sizeof(prefs));
  prefs.frameInfo.contentSize = size;
  out.resize(LZ4F_compressFrameBound(size, &prefs));
  const std::size_t packed = LZ4F_compressFrame(out.data(), out.size(), data, size, &prefs);
  if (LZ4F_isError(packed)) throw std::runtime_error(std::string("LZ4 compression failed: ") + LZ4F_getErrorName(packed));
  return packed;
}

// One zstd frame of `size` bytes into `out` at zstd's default level, as DV's ZSTD writes its
// packets; returns its size.
std::size_t zstd_frame(const char* data, std::size_t size, std::vector<char>& out) {
  out.resize(ZSTD_compressBound(size));
  const std::size_t packed = ZSTD_compress(out.data(), out.size(), data, size, ZSTD_CLEVEL_DEFAULT);
  if (ZSTD_isError(packed)) throw std::runtime_error(std::string("zstd compression failed: ") + ZSTD_getErrorName(packed));
  return packed;
}

dv::CompressionType header_compression(Aedat4Compression c) {
  switch (c) {
    case Aedat4Compression::Lz4: return dv::CompressionType_LZ4;
    case Aedat4Compression::Zstd: return dv::CompressionType_ZSTD;
    case Aedat4Compression::None: break;
  }
  return dv::CompressionType_NONE;
}

// FlatBuffers reads its scalars in place and needs them aligned; in a file they lie wherever the
// previous bytes end (the IOHeader starts at byte 14), so each buffer is read from a copy.
class AlignedCopy {
 public:
  AlignedCopy(const char* data, std::size_t size) : words_((size + 7) / 8), size_(size) {
    if (size > 0) std::memcpy(words_.data(), data, size);
  }
  const std::uint8_t* data() const { return reinterpret_cast<const std::uint8_t*>(words_.data()); }
  std::size_t size() const { return size_; }

 private:
  std::vector<std::uint64_t> words_;
  std::size_t size_;
};

int parse_size(const std::string& text, const std::string& label, const char* key) {
  try {
    std::size_t used = 0;
    const long v = std::stol(text, &used);
    if (used == text.size() && v >= 1 && v <= 4096) return static_cast<int>(v);
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("event file '{}': info node {} '{}' is not a size from 1 to 4096", label, key, text));
}

}  // namespace

Aedat4Compression parse_aedat4_compression(const std::string& text) {
  if (text == "lz4") return Aedat4Compression::Lz4;
  if (text == "none") return Aedat4Compression::None;
  if (text == "zstd") return Aedat4Compression::Zstd;
  throw InputError(fmt::format("--aedat4-compression: expected lz4, zstd or none (got '{}')", text));
}

// The packet filling, the buffers written packets gave back, and the thread that compresses and
// writes full ones (none uncompressed).
struct Aedat4Writer::Packets {
  // A packet's FlatBuffer and its compressed frame. They go with the packet to the writer's thread
  // and come back once it is written, to be built into again: 64 KiB allocated for each packet
  // and freed on another thread goes back to the system and is faulted in, zeroed, the next time
  // (48 k page faults writing 50 M events against 7.5 k reused, 5 % of the run's CPU).
  struct Buffers {
    flatbuffers::FlatBufferBuilder fbb{kAedat4PacketEvents * sizeof(dv::Event) + 64};
    std::vector<char> packed;
    std::size_t packed_size = 0;
    // Whose the compression is: the writer's thread's, or the caller's when it finishes the file
    // (it compresses the packets still waiting from the newest while the writer's thread works
    // from the oldest). Set once, under `claims`; `packed_ready` once its frame is in `packed`.
    bool claimed = false, packed_ready = false, pack_failed = false;
  };

  // The packet being filled, built in place: a full packet's vector of events is reserved in its
  // FlatBuffer when the packet opens and the events are written straight into it (copying 64 KiB
  // of events a packet into the FlatBuffer was a pass over every event). Its first `filled` events.
  std::shared_ptr<Buffers> open;
  dv::Event* filling = nullptr;
  flatbuffers::Offset<flatbuffers::Vector<const dv::Event*>> events_vector;
  std::size_t filled = 0;
  std::mutex spare_mutex;
  std::vector<std::shared_ptr<Buffers>> spare;
  // Packets handed to the writer's thread and not yet claimed for compression, oldest first.
  std::mutex claims;
  std::condition_variable packed_changed;
  std::deque<std::shared_ptr<Buffers>> unclaimed;
  std::unique_ptr<SerialWorker> worker;

  std::shared_ptr<Buffers> take() {
    {
      std::lock_guard<std::mutex> lock(spare_mutex);
      if (!spare.empty()) {
        std::shared_ptr<Buffers> b = std::move(spare.back());
        spare.pop_back();
        b->fbb.Clear();
        b->claimed = b->packed_ready = b->pack_failed = false;
        return b;
      }
    }
    return std::make_shared<Buffers>();
  }
  void give_back(std::shared_ptr<Buffers> b) {
    std::lock_guard<std::mutex> lock(spare_mutex);
    spare.push_back(std::move(b));
  }
  void open_packet() {
    open = take();
    events_vector = open->fbb.CreateUninitializedVectorOfStructs(kAedat4PacketEvents, &filling);
    filled = 0;
  }
  // Claims `b`'s compression for the writer's thread, which takes the packets oldest first (the
  // front of `unclaimed`): false when the caller has it.
  bool claim(Buffers& b) {
    std::lock_guard<std::mutex> lock(claims);
    if (b.claimed) return false;
    b.claimed = true;
    if (!unclaimed.empty() && unclaimed.front().get() == &b) unclaimed.pop_front();
    return true;
  }
  // Compresses `b`, and says so to the writer's thread waiting for it, also when compression
  // fails (it then fails the packet's write rather than wait for ever).
  void pack(Buffers& b, const Aedat4Writer& writer) {
    std::exception_ptr error;
    try {
      b.packed_size = writer.compress(reinterpret_cast<const char*>(b.fbb.GetBufferPointer()), b.fbb.GetSize(), b.packed);
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(claims);
      b.packed_ready = true;
      b.pack_failed = error != nullptr;
    }
    packed_changed.notify_all();
    if (error) std::rethrow_exception(error);
  }
};

// Packets waiting for the writer's thread (64 KiB each, 4 MiB in all): deep enough that it goes on
// compressing while the merge waits for the tiles' next window (with 8, .aedat4 was written at 0.54
// of LZ4's rate alone; with 64, 0.62: event_rate_bench).
constexpr std::size_t kPacketsWaiting = 64;

Aedat4Writer::Aedat4Writer(std::ostream& out, const EventFileSpec& spec)
    : out_(out), stamps_(spec.tick), compression_(spec.compression) {
  const std::streamoff start = out_.tellp();
  out_.write(kAedat4Magic, static_cast<std::streamsize>(kAedat4MagicBytes));
  // dataTablePosition is known only at the end: written now as a value no file holds, found in the
  // header's bytes, and patched there when the table is written.
  constexpr std::int64_t kPlaceholder = 0x7A65'5369'6D41'6154;
  flatbuffers::FlatBufferBuilder fbb;
  fbb.ForceDefaults(true);
  const auto info = fbb.CreateString(info_node(spec));
  const auto header = dv::CreateIOHeader(fbb, header_compression(compression_), kPlaceholder, info);
  dv::FinishSizePrefixedIOHeaderBuffer(fbb, header);
  const char* bytes = reinterpret_cast<const char*>(fbb.GetBufferPointer());
  const std::string_view view(bytes, fbb.GetSize());
  char pattern[8];
  std::memcpy(pattern, &kPlaceholder, 8);  // FlatBuffers stores little-endian, as this machine does
  const auto at = view.find(std::string_view(pattern, 8));
  if (start >= 0 && at != std::string_view::npos) {
    table_field_at_ = static_cast<std::int64_t>(start) + static_cast<std::int64_t>(kAedat4MagicBytes + at);
  }
  std::string header_bytes(view);
  if (at != std::string_view::npos) {
    const std::int64_t none = -1;
    std::memcpy(header_bytes.data() + at, &none, 8);
  }
  out_.write(header_bytes.data(), static_cast<std::streamsize>(header_bytes.size()));
  packets_ = std::make_unique<Packets>();
  if (compression_ != Aedat4Compression::None) packets_->worker = std::make_unique<SerialWorker>(kPacketsWaiting);
}

// The worker goes first: a job still running uses the members.
Aedat4Writer::~Aedat4Writer() { packets_->worker.reset(); }

void Aedat4Writer::events(const AddressEvent* first, std::size_t count) {
  for (std::size_t i = 0; i < count;) {
    if (!packets_->open) packets_->open_packet();
    // As many as the packet has room for, counted in a local.
    dv::Event* const packet = packets_->filling;
    std::size_t filled = packets_->filled;
    const std::size_t n = std::min(count - i, kAedat4PacketEvents - filled);
    for (const AddressEvent* e = first + i; e != first + i + n; ++e) {
      packet[filled++] = dv::Event(static_cast<std::int64_t>(stamps_(e->t)), static_cast<std::int16_t>(e->x),
                                   static_cast<std::int16_t>(e->y), e->flags != kGhostEvent);
    }
    packets_->filled = filled;
    i += n;
    if (filled == kAedat4PacketEvents) write_packet();
  }
}

std::size_t Aedat4Writer::compress(const char* body, std::size_t size, std::vector<char>& out) const {
  switch (compression_) {
    case Aedat4Compression::Lz4: return lz4_frame(body, size, out);
    case Aedat4Compression::Zstd: return zstd_frame(body, size, out);
    case Aedat4Compression::None: break;
  }
  out.assign(body, body + size);
  return size;
}

void Aedat4Writer::write_packet() {
  const std::size_t filled = packets_->filled;
  // An empty run still gets one (empty) packet: readers that gather the event packets (tonic's)
  // fail on a file with none.
  if (filled == 0 && any_packet_) return;
  any_packet_ = true;
  std::shared_ptr<Packets::Buffers> buffers = std::move(packets_->open);
  const dv::Event* events = packets_->filling;
  flatbuffers::Offset<flatbuffers::Vector<const dv::Event*>> vector = packets_->events_vector;
  if (filled < kAedat4PacketEvents) {
    // The last packet, short of full: its events copied into a FlatBuffer of their number.
    std::shared_ptr<Packets::Buffers> reserved = std::move(buffers);
    buffers = std::make_shared<Packets::Buffers>();
    static const dv::Event kNone{};
    vector = buffers->fbb.CreateVectorOfStructs(filled == 0 ? &kNone : events, filled);
    if (reserved) packets_->give_back(std::move(reserved));
  }
  flatbuffers::FlatBufferBuilder& fbb = buffers->fbb;
  dv::FinishSizePrefixedEventPacketBuffer(fbb, dv::CreateEventPacket(fbb, vector));
  const Written entry{-1, 0, static_cast<std::int64_t>(filled), filled == 0 ? 0 : events[0].timestamp(),
                      filled == 0 ? 0 : events[filled - 1].timestamp()};
  packets_->filled = 0;
  packets_->filling = nullptr;
  const char* plain = reinterpret_cast<const char*>(fbb.GetBufferPointer());
  if (!packets_->worker) {  // uncompressed
    write_body(plain, fbb.GetSize(), entry);
    packets_->give_back(std::move(buffers));
    return;
  }
  // Compressed on the writer's thread; or here, while that thread is behind (half its queue
  // waiting), so that this thread compresses rather than waits. Written there, in order, either way.
  if (packets_->worker->waiting() >= kPacketsWaiting / 2) {
    buffers->claimed = true;
    packets_->pack(*buffers, *this);
  } else {
    std::lock_guard<std::mutex> lock(packets_->claims);
    packets_->unclaimed.push_back(buffers);
  }
  packets_->worker->post([this, buffers, entry] {
    if (packets_->claim(*buffers)) {
      packets_->pack(*buffers, *this);
    } else {
      std::unique_lock<std::mutex> lock(packets_->claims);
      packets_->packed_changed.wait(lock, [&] { return buffers->packed_ready; });
      if (buffers->pack_failed) throw std::runtime_error("an .aedat4 packet could not be compressed");
    }
    write_body(buffers->packed.data(), buffers->packed_size, entry);
    packets_->give_back(buffers);
  });
}

// Compresses the packets still waiting from the newest back, while the writer's thread compresses
// and writes them from the oldest: the end of a run's file is not left to one core.
void Aedat4Writer::help_pack() {
  for (;;) {
    std::shared_ptr<Packets::Buffers> b;
    {
      std::lock_guard<std::mutex> lock(packets_->claims);
      while (!packets_->unclaimed.empty() && !b) {
        std::shared_ptr<Packets::Buffers> newest = std::move(packets_->unclaimed.back());
        packets_->unclaimed.pop_back();
        if (!newest->claimed) {
          newest->claimed = true;
          b = std::move(newest);
        }
      }
    }
    if (!b) return;
    packets_->pack(*b, *this);
  }
}

void Aedat4Writer::write_body(const char* body, std::size_t size, Written entry) {
  const std::streamoff at = out_.tellp();
  put_le32(out_, 0);  // stream id
  put_le32(out_, static_cast<std::uint32_t>(size));
  out_.write(body, static_cast<std::streamsize>(size));
  entry.offset = at < 0 ? -1 : static_cast<std::int64_t>(at) + 8;
  entry.size = static_cast<std::int64_t>(size);
  written_.push_back(entry);
}

void Aedat4Writer::finish() {
  write_packet();
  if (packets_->worker) {
    help_pack();
    packets_->worker->drain();
  }
  write_data_table();
  // Ends the file's writes now (an output file gives back the space it reserved ahead of them).
  out_.flush();
}

// DV's FileDataTable after the last packet, compressed as the packets are, and the header's
// dataTablePosition set to it: readers that seek (aestream) find the packets through it.
void Aedat4Writer::write_data_table() {
  const std::streamoff position = out_.tellp();
  if (table_field_at_ < 0 || position < 0) return;  // an output that cannot seek keeps -1: readers walk the packets
  flatbuffers::FlatBufferBuilder fbb;
  std::vector<flatbuffers::Offset<dv::FileDataDefinition>> entries;
  for (const Written& w : written_) {
    const dv::PacketHeader info(0, static_cast<std::int32_t>(w.size));
    entries.push_back(dv::CreateFileDataDefinition(fbb, w.offset, &info, w.elements, w.first_us, w.last_us));
  }
  dv::FinishSizePrefixedFileDataTableBuffer(fbb, dv::CreateFileDataTable(fbb, fbb.CreateVector(entries)));
  const char* body = reinterpret_cast<const char*>(fbb.GetBufferPointer());
  const std::size_t size = compress(body, fbb.GetSize(), body_);
  out_.write(body_.data(), static_cast<std::streamsize>(size));
  const std::streamoff end = out_.tellp();
  const std::int64_t value = static_cast<std::int64_t>(position);
  char le[8];
  std::memcpy(le, &value, 8);
  out_.seekp(table_field_at_);
  out_.write(le, 8);
  out_.seekp(end);
}

PolarityRecording decode_aedat4(const std::string& data, const std::string& label) {
  if (data.compare(0, kAedat4MagicBytes, kAedat4Magic) != 0) {
    throw InputError(fmt::format("event file '{}': not AEDAT 4.0 (must start with #!AER-DAT4.0)", label));
  }
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t pos = kAedat4MagicBytes;
  if (data.size() < pos + 4) throw InputError(fmt::format("event file '{}': truncated in the IOHeader", label));
  const std::uint64_t header_size = get_le32(bytes + pos);
  if (header_size > data.size() - pos - 4) throw InputError(fmt::format("event file '{}': truncated in the IOHeader", label));
  const AlignedCopy header_bytes(data.data() + pos, header_size + 4);
  {
    flatbuffers::Verifier v(header_bytes.data(), header_bytes.size());
    if (!dv::VerifySizePrefixedIOHeaderBuffer(v)) {
      throw InputError(fmt::format("event file '{}': the IOHeader is not a valid FlatBuffer", label));
    }
  }
  const dv::IOHeader* header = dv::GetSizePrefixedIOHeader(header_bytes.data());
  const dv::CompressionType compression = header->compression();
  if (compression != dv::CompressionType_NONE && compression != dv::CompressionType_LZ4 &&
      compression != dv::CompressionType_LZ4_HIGH && compression != dv::CompressionType_ZSTD &&
      compression != dv::CompressionType_ZSTD_HIGH) {
    throw InputError(fmt::format("event file '{}': compression {} is not supported (aesim reads none, LZ4 and ZSTD)",
                                 label, static_cast<int>(compression)));
  }
  const bool lz4 = compression == dv::CompressionType_LZ4 || compression == dv::CompressionType_LZ4_HIGH;
  const bool zstd = compression == dv::CompressionType_ZSTD || compression == dv::CompressionType_ZSTD_HIGH;
  pos += 4 + header_size;
  // Packets run up to the data table, where the header says it lies (DV writes one at the end).
  std::size_t packets_end = data.size();
  const std::int64_t table = header->dataTablePosition();
  if (table >= 0) {
    if (static_cast<std::uint64_t>(table) > data.size()) {
      throw InputError(fmt::format("event file '{}': truncated: its header puts the data table at byte {}, past the end "
                                   "({} bytes)", label, table, data.size()));
    }
    if (static_cast<std::uint64_t>(table) < pos) {
      throw InputError(fmt::format("event file '{}': dataTablePosition {} lies inside the header", label, table));
    }
    packets_end = static_cast<std::size_t>(table);
  }

  // The events stream: the first output node whose type is EVTS; its info gives the array size.
  // Every stream the header declares, with its type, so that other streams' packets are counted.
  PolarityRecording rec;
  long events_stream = -1;
  std::map<long, std::string> declared;
  const std::string xml = header->infoNode() ? header->infoNode()->str() : "";
  for (std::size_t node = xml.find("<node name=\""); node != std::string::npos;
       node = xml.find("<node name=\"", node + 1)) {
    const std::size_t name_end = xml.find('"', node + 12);
    if (name_end == std::string::npos) break;
    const std::string name = xml.substr(node + 12, name_end - node - 12);
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos || name.size() > 9) continue;
    // This stream's attributes run to the next sibling stream (or the end).
    std::size_t next = xml.find("<node name=\"", name_end);
    while (next != std::string::npos && xml.compare(next + 12, 4, "info") == 0) next = xml.find("<node name=\"", next + 1);
    const auto attrs = xml_attrs(xml.substr(node, next == std::string::npos ? std::string::npos : next - node));
    std::string type;
    for (const auto& [key, value] : attrs) {
      if (key == "typeIdentifier") type = value;
    }
    declared.emplace(std::stol(name), type);
    if (type != "EVTS" || events_stream >= 0) continue;
    events_stream = std::stol(name);
    for (const auto& [key, value] : attrs) {
      if (key == "sizeX") rec.width = parse_size(value, label, "sizeX");
      if (key == "sizeY") rec.height = parse_size(value, label, "sizeY");
      if (key.rfind("aesim.sensor.", 0) == 0) rec.sensor[key.substr(13)] = value;
    }
  }
  if (events_stream < 0) throw InputError(fmt::format("event file '{}': no stream of events (EVTS) in its header", label));

  std::vector<char> plain;
  std::uint64_t decoded = 0;
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(nullptr, &LZ4F_freeDecompressionContext);
  if (lz4) {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) throw std::bad_alloc();
    dctx.reset(ctx);
  }
  std::unique_ptr<ZSTD_DStream, decltype(&ZSTD_freeDStream)> dstream(nullptr, &ZSTD_freeDStream);
  if (zstd) {
    dstream.reset(ZSTD_createDStream());
    if (!dstream) throw std::bad_alloc();
  }
  std::map<long, SkippedPackets> skipped;
  for (std::size_t packet = 0; pos < packets_end; ++packet) {
    if (packets_end - pos < 8) throw InputError(fmt::format("event file '{}': packet {} is truncated", label, packet));
    const std::int32_t stream = static_cast<std::int32_t>(get_le32(bytes + pos));
    const std::uint64_t size = get_le32(bytes + pos + 4);
    pos += 8;
    if (size > packets_end - pos) throw InputError(fmt::format("event file '{}': packet {} is truncated", label, packet));
    const char* body = data.data() + pos;
    pos += size;
    const auto kind = declared.find(stream);
    if (kind == declared.end()) {
      throw InputError(fmt::format("event file '{}': packet {} belongs to stream {}, which the header does not declare",
                                   label, packet, stream));
    }
    if (stream != events_stream) {
      SkippedPackets& s = skipped[stream];
      s.type = kind->second.empty() ? "stream " + std::to_string(stream) : kind->second;
      ++s.packets;
      s.bytes += size;
      continue;
    }
    std::size_t body_size = size;
    // Both compressions decode into `plain` as it grows, so that a frame claiming gigabytes costs
    // only what it really holds, up to the packet limit: the bytes already decoded, and room made.
    const auto grow = [&](std::vector<char>& buffer, std::size_t index) {
      const std::size_t at = buffer.size();
      if (at >= kAedat4MaxPacketBytes) {
        throw InputError(fmt::format("event file '{}': packet {} decompresses to more than {} bytes", label, index,
                                     kAedat4MaxPacketBytes));
      }
      buffer.resize(std::max<std::size_t>(2 * at, 1 << 16));
      return at;
    };
    if (lz4) {
      plain.clear();
      LZ4F_resetDecompressionContext(dctx.get());
      std::size_t in_at = 0;
      for (;;) {
        const std::size_t at = grow(plain, packet);
        std::size_t out_size = plain.size() - at, in_size = size - in_at;
        const std::size_t hint = LZ4F_decompress(dctx.get(), plain.data() + at, &out_size, body + in_at, &in_size, nullptr);
        if (LZ4F_isError(hint)) {
          throw InputError(fmt::format("event file '{}': packet {}: LZ4: {}", label, packet, LZ4F_getErrorName(hint)));
        }
        in_at += in_size;
        plain.resize(at + out_size);
        if (hint == 0) break;
        if (in_at == size && out_size == 0) {
          throw InputError(fmt::format("event file '{}': packet {}: the LZ4 frame is truncated", label, packet));
        }
      }
      body = plain.data();
      body_size = plain.size();
    } else if (zstd) {
      plain.clear();
      ZSTD_initDStream(dstream.get());
      ZSTD_inBuffer in{body, size, 0};
      for (;;) {
        const std::size_t at = grow(plain, packet);
        ZSTD_outBuffer out{plain.data() + at, plain.size() - at, 0};
        const std::size_t hint = ZSTD_decompressStream(dstream.get(), &out, &in);
        if (ZSTD_isError(hint)) {
          throw InputError(fmt::format("event file '{}': packet {}: zstd: {}", label, packet, ZSTD_getErrorName(hint)));
        }
        plain.resize(at + out.pos);
        if (hint == 0) break;
        if (in.pos == in.size && out.pos < out.size) {
          throw InputError(fmt::format("event file '{}': packet {}: the zstd frame is truncated", label, packet));
        }
      }
      body = plain.data();
      body_size = plain.size();
    }
    decoded += body_size;
    if (decoded > kAedat4MaxDecodedBytes) {
      throw InputError(fmt::format("event file '{}': more than {} bytes of events", label, kAedat4MaxDecodedBytes));
    }
    const AlignedCopy aligned(body, body_size);
    flatbuffers::Verifier v(aligned.data(), aligned.size());
    if (!dv::VerifySizePrefixedEventPacketBuffer(v)) {
      throw InputError(fmt::format("event file '{}': packet {} is not a valid EventPacket", label, packet));
    }
    const dv::EventPacket* p = dv::GetSizePrefixedEventPacket(aligned.data());
    if (!p->elements()) continue;
    // The verifier checks the vector's length word, 4-byte aligned; its 16-byte events may still
    // sit off their 8-byte alignment in a crafted file, so each is copied out before it is read.
    const std::uint8_t* raw = p->elements()->Data();
    for (flatbuffers::uoffset_t i = 0; i < p->elements()->size(); ++i) {
      dv::Event e;
      std::memcpy(static_cast<void*>(&e), raw + i * sizeof(dv::Event), sizeof(dv::Event));
      PolarityEvent out;
      out.t_us = e.timestamp();
      out.x = e.x();
      out.y = e.y();
      out.on = e.polarity();
      rec.events.push_back(out);
    }
  }
  for (auto& [stream, s] : skipped) rec.skipped.push_back(s);
  return rec;
}

void put_in_time_order(PolarityRecording& rec) {
  const std::vector<PolarityEvent>& e = rec.events;
  for (std::size_t i = 1; i < e.size(); ++i) rec.reordered += e[i].t_us < e[i - 1].t_us ? 1 : 0;
  if (rec.reordered > 0) {
    std::stable_sort(rec.events.begin(), rec.events.end(),
                     [](const PolarityEvent& a, const PolarityEvent& b) { return a.t_us < b.t_us; });
  }
}

}  // namespace aesim
