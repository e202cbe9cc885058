#include "aesim/event_files/dsec_h5.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>


#include <fmt/format.h>
#include <hdf5.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/ecf_codec.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/forked_reader.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/output/temp_files.hpp"

namespace aesim {
namespace h5 {

// Closes an HDF5 handle of any kind when it leaves scope.
class Handle {
 public:
  explicit Handle(hid_t id = H5I_INVALID_HID) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_) { o.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& o) noexcept {
    std::swap(id_, o.id_);
    return *this;
  }
  ~Handle() {
    if (id_ < 0) return;
    switch (H5Iget_type(id_)) {
      case H5I_FILE: H5Fclose(id_); break;
      case H5I_GROUP: H5Gclose(id_); break;
      case H5I_DATASET: H5Dclose(id_); break;
      case H5I_DATASPACE: H5Sclose(id_); break;
      case H5I_DATATYPE: H5Tclose(id_); break;
      case H5I_ATTR: H5Aclose(id_); break;
      case H5I_GENPROP_LST: H5Pclose(id_); break;
      default: break;
    }
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
};

}  // namespace h5

namespace {

using h5::Handle;

constexpr std::size_t kDsecChunk = std::size_t(1) << 14;  // elements per chunk and per append

// HDF5 prints its own error stack unless told not to; aesim reports one line instead. And HDF5's
// exit handler closes the files still open: one whose last write failed (a full disk) it crashes
// on (HDF5 1.10, H5F__close_cb), so it registers none; the system takes back what is left.
void quiet_hdf5() {
  static const bool once = [] {
    H5dont_atexit();
    return true;
  }();
  (void)once;
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Handle checked(hid_t id, const std::string& what) {
  if (id < 0) throw OutputError(what);
  return Handle(id);
}

// Creation properties of the file, a group or a dataset without the times HDF5 records in each
// object's header by default: they would make two runs of the same inputs differ in bytes.
Handle untimed(hid_t property_class) {
  Handle props = checked(H5Pcreate(property_class), "HDF5: cannot make creation properties");
  H5Pset_obj_track_times(props.get(), false);
  return props;
}

Handle extendable(hid_t parent, const char* name, hid_t type) {
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = kDsecChunk;
  Handle space = checked(H5Screate_simple(1, &zero, &unlimited), "HDF5: cannot make a dataspace");
  Handle props = untimed(H5P_DATASET_CREATE);
  H5Pset_chunk(props.get(), 1, &chunk);
  return checked(H5Dcreate2(parent, name, type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
                 fmt::format("HDF5: cannot create dataset {}", name));
}

void append(hid_t dataset, hid_t type, const void* data, hsize_t at, hsize_t count) {
  if (count == 0) return;
  const hsize_t size = at + count;
  // The system's reason alone (a full disk: "No space left on device"); the writer names the file.
  if (H5Dset_extent(dataset, &size) < 0) throw OutputError(std::strerror(errno ? errno : EIO));
  Handle file_space = checked(H5Dget_space(dataset), "HDF5: no dataspace");
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &at, nullptr, &count, nullptr);
  Handle memory = checked(H5Screate_simple(1, &count, nullptr), "HDF5: cannot make a dataspace");
  if (H5Dwrite(dataset, type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0) {
    throw OutputError(std::strerror(errno ? errno : EIO));
  }
}

void string_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = checked(H5Tcopy(H5T_C_S1), "HDF5: string type");
  H5Tset_size(type.get(), std::max<std::size_t>(1, value.size()));
  Handle space = checked(H5Screate(H5S_SCALAR), "HDF5: scalar space");
  Handle attr = checked(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        fmt::format("HDF5: cannot create attribute {}", name));
  H5Awrite(attr.get(), type.get(), value.c_str());
}

void int_attribute(hid_t object, const char* name, long long value) {
  Handle space = checked(H5Screate(H5S_SCALAR), "HDF5: scalar space");
  Handle attr = checked(H5Acreate2(object, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                        fmt::format("HDF5: cannot create attribute {}", name));
  H5Awrite(attr.get(), H5T_NATIVE_LLONG, &value);
}

}  // namespace

struct DsecWriter::Handles {
  h5::Handle file, events, x, y, t, p;
};

DsecWriter::DsecWriter(const std::string& path, const EventFileSpec& spec, double duration_s)
    : h_(std::make_unique<Handles>()), path_(path), stamps_(spec.tick), ms_total_(static_cast<std::uint64_t>(std::ceil(duration_s * 1e3))) {
  quiet_hdf5();
  h_->file = checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, untimed(H5P_FILE_CREATE).get(), H5P_DEFAULT),
                     fmt::format("cannot create HDF5 file '{}'", path));
  h_->events = checked(H5Gcreate2(h_->file.get(), "events", H5P_DEFAULT, untimed(H5P_GROUP_CREATE).get(), H5P_DEFAULT),
                       "HDF5: cannot create /events");
  h_->x = extendable(h_->events.get(), "x", H5T_STD_U16LE);
  h_->y = extendable(h_->events.get(), "y", H5T_STD_U16LE);
  h_->t = extendable(h_->events.get(), "t", H5T_STD_U32LE);
  h_->p = extendable(h_->events.get(), "p", H5T_STD_U8LE);
  int_attribute(h_->events.get(), "width", spec.array.cols);
  int_attribute(h_->events.get(), "height", spec.array.rows);
  for (const auto& [key, value] : spec.sensor) string_attribute(h_->file.get(), "aesim.sensor." + key, value);
  for (auto* v : {&x_, &y_}) v->reserve(kDsecChunk);
  t_.reserve(kDsecChunk);
  p_.reserve(kDsecChunk);
}

DsecWriter::~DsecWriter() = default;

void DsecWriter::events(const AddressEvent* first, std::size_t count) {
  for (std::size_t i = 0; i < count; ++i) {
    const AddressEvent& e = first[i];
    const std::uint64_t t = stamps_(e.t);
    if (t > 0xFFFFFFFFu) {
      throw InputError(fmt::format("DSEC stamps are uint32 microseconds: an event at {:.6g} s does not fit (at most "
                                   "4294 s)", e.t));
    }
    while (ms_to_idx_.size() * 1000 <= t) ms_to_idx_.push_back(count_);
    x_.push_back(static_cast<std::uint16_t>(e.x));
    y_.push_back(static_cast<std::uint16_t>(e.y));
    t_.push_back(static_cast<std::uint32_t>(t));
    p_.push_back(e.flags == kGhostEvent ? 0 : 1);
    ++count_;
    if (x_.size() == kDsecChunk) flush();
  }
}

void DsecWriter::flush() {
  const hsize_t n = x_.size();
  try {
    append(h_->x.get(), H5T_NATIVE_UINT16, x_.data(), written_, n);
    append(h_->y.get(), H5T_NATIVE_UINT16, y_.data(), written_, n);
    append(h_->t.get(), H5T_NATIVE_UINT32, t_.data(), written_, n);
    append(h_->p.get(), H5T_NATIVE_UINT8, p_.data(), written_, n);
  } catch (const OutputError& e) {
    throw OutputError(fmt::format("writing '{}' failed: {}", target_of(path_), e.what()));
  }
  written_ += n;
  x_.clear();
  y_.clear();
  t_.clear();
  p_.clear();
}

std::string DsecWriter::reader_warning() const {
  return count_ == 0 ? "it holds no events, and DSEC's EventSlicer cannot open a file without a last stamp "
                       "(h5py and aesim's readers can)"
                     : "";
}

void DsecWriter::finish() {
  flush();
  while (ms_to_idx_.size() <= ms_total_) ms_to_idx_.push_back(count_);
  const hsize_t n = ms_to_idx_.size();
  Handle space = checked(H5Screate_simple(1, &n, nullptr), "HDF5: cannot make a dataspace");
  Handle index = checked(H5Dcreate2(h_->file.get(), "ms_to_idx", H5T_STD_U64LE, space.get(), H5P_DEFAULT,
                                    untimed(H5P_DATASET_CREATE).get(), H5P_DEFAULT),
                         "HDF5: cannot create /ms_to_idx");
  if (H5Dwrite(index.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, ms_to_idx_.data()) < 0) {
    throw OutputError("HDF5: writing /ms_to_idx failed");
  }
  Handle scalar = checked(H5Screate(H5S_SCALAR), "HDF5: scalar space");
  Handle offset = checked(H5Dcreate2(h_->file.get(), "t_offset", H5T_STD_I64LE, scalar.get(), H5P_DEFAULT,
                                     untimed(H5P_DATASET_CREATE).get(), H5P_DEFAULT),
                          "HDF5: cannot create /t_offset");
  const long long zero = 0;
  H5Dwrite(offset.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &zero);
  errno = 0;
  if (H5Fflush(h_->file.get(), H5F_SCOPE_GLOBAL) < 0) throw OutputError(write_failure(path_));
  h_ = std::make_unique<Handles>();  // the file is closed and complete
}

namespace {

// Refuses what would make HDF5 read beyond the file it was given: a link to another file, data
// stored in other files, a virtual dataset.
void require_local(hid_t file, const char* name, const std::string& path, const char* group = "/events") {
  // Every link on the way (/events, then /events/x).
  std::string sofar;
  for (const std::string& part : {std::string(group), std::string(name)}) {
    if (part == sofar) continue;
    sofar = part;
    if (H5Lexists(file, part.c_str(), H5P_DEFAULT) <= 0) return;
    H5L_info_t info{};
    if (H5Lget_info(file, part.c_str(), &info, H5P_DEFAULT) >= 0 && info.type != H5L_TYPE_HARD) {
      throw InputError(fmt::format("event file '{}': {} is {} link; aesim reads datasets stored in the file itself", path, part,
                                   info.type == H5L_TYPE_EXTERNAL ? "an external" : "a soft"));
    }
  }
}

// A filter the dataset needs that this HDF5 cannot decode, named: "filter 32001 (blosc)".
std::string missing_filter(hid_t dcpl) {
  const int n = H5Pget_nfilters(dcpl);
  for (int i = 0; i < n; ++i) {
    unsigned flags = 0, config = 0;
    std::size_t cd_count = 0;
    char name[64] = {};
    const H5Z_filter_t id = H5Pget_filter2(dcpl, static_cast<unsigned>(i), &flags, &cd_count, nullptr, sizeof name, name, &config);
    if (id >= 0 && H5Zfilter_avail(id) <= 0) return fmt::format("filter {} ({})", static_cast<int>(id), name[0] ? name : "unnamed");
  }
  return "";
}

// Prophesee's self-assigned HDF5 filter code of its ECF codec, which Metavision's HDF5 event files use.
constexpr H5Z_filter_t kEcfFilter = 0x8ECF;

// Why the last ECF chunk this thread decoded was refused, for the read's error.
thread_local std::string ecf_refusal;

// HDF5's filter callback for ECF, reading only (aesim writes no ECF): each chunk one ECF block,
// decoded into Metavision's 16-byte events. No exception crosses HDF5's C code: a refused block
// is 0 bytes, which fails the read.
std::size_t ecf_filter(unsigned flags, std::size_t, const unsigned[], std::size_t bytes, std::size_t* buffer_bytes, void** buffer) {
  if ((flags & H5Z_FLAG_REVERSE) == 0) {
    ecf_refusal = "aesim decodes ECF, it does not encode it";
    return 0;
  }
  try {
    void* out = std::malloc(kEcfMostEvents * kEcfEventBytes);
    if (out == nullptr) throw std::bad_alloc();
    std::size_t made = 0;
    try {
      made = decode_ecf_block(static_cast<const unsigned char*>(*buffer), bytes, static_cast<unsigned char*>(out));
    } catch (...) {
      std::free(out);
      throw;
    }
    std::free(*buffer);
    *buffer = out;
    *buffer_bytes = kEcfMostEvents * kEcfEventBytes;
    return made;
  } catch (const std::exception& e) {
    ecf_refusal = e.what();
    return 0;
  }
}

// ECF's decoder, registered with this process's HDF5 once, so that Metavision's files read without
// Prophesee's plugin (which, on HDF5_PLUGIN_PATH, this one stands in for).
void register_ecf_decoder() {
  static const bool once = [] {
    static const H5Z_class2_t ecf = {H5Z_CLASS_T_VERS, kEcfFilter, 1, 1, "Prophesee's ECF, decoded by aesim", nullptr, nullptr,
                                     ecf_filter};
    return H5Zregister(&ecf) >= 0;
  }();
  (void)once;
}

// A dataset of `n` records, checked against the bytes the file holds before anything is read: its
// data in the file itself, its filters ones this HDF5 decodes, its claimed length one the file's
// bytes can hold.
void check_stored(hid_t d, hid_t stored, hsize_t n, const char* name, const std::string& path, std::uintmax_t file_bytes) {
  Handle dcpl(H5Dget_create_plist(d));
  if (dcpl.ok() && H5Pget_external_count(dcpl.get()) > 0) {
    throw InputError(fmt::format("event file '{}': {} keeps its data in other files", path, name));
  }
  if (dcpl.ok() && H5Pget_layout(dcpl.get()) == H5D_VIRTUAL) {
    throw InputError(fmt::format("event file '{}': {} is a virtual dataset (data in other files)", path, name));
  }
  if (dcpl.ok()) {
    const std::string filter = missing_filter(dcpl.get());
    if (!filter.empty()) {
      throw InputError(fmt::format("event file '{}': {} is compressed with HDF5 {}, which this HDF5 cannot decode "
                                   "(install its plugin, or write the file without it)",
                                   path, name, filter));
    }
  }
  // Stored bytes, compressed or not, within the file; decompressed, at most 1000 times more (far
  // past what HDF5's filters reach on event streams).
  const std::uint64_t element = H5Tget_size(stored);
  const haddr_t storage = H5Dget_storage_size(d);
  const double claimed = static_cast<double>(n) * static_cast<double>(element);
  if (n > 0 && (storage == 0 || static_cast<double>(storage) * 1000.0 < claimed || storage > file_bytes)) {
    throw InputError(fmt::format("event file '{}': {} claims {} entries ({:.3g} bytes) but the file stores {} bytes of it",
                                 path, name, n, claimed, storage));
  }
  if (n > (hsize_t(1) << 32)) throw InputError(fmt::format("event file '{}': {} has more than 2^32 events", path, name));
}

// A 1-D dataset of integers, opened and checked (check_stored) before anything is read.
struct Column {
  Handle d;
  hsize_t n = 0;
  bool real = false;  // floats (a time column only)
};
// `first`: the group's first column, whose length the others must have (`expected`).
Column open_column(hid_t file, const char* name, const char* group, const std::string& path, const char* first,
                   hsize_t expected, std::uintmax_t file_bytes, bool floats_allowed = false) {
  require_local(file, name, path, group);
  Column c;
  c.d = Handle(H5Dopen2(file, name, H5P_DEFAULT));
  if (!c.d.ok()) throw InputError(fmt::format("event file '{}': no dataset {} (not the DSEC layout)", path, name));
  Handle space(H5Dget_space(c.d.get()));
  Handle stored(H5Dget_type(c.d.get()));
  c.real = floats_allowed && H5Tget_class(stored.get()) == H5T_FLOAT;
  // h5py stores NumPy's bools as an enum of FALSE and TRUE over a byte.
  const bool boolean = H5Tget_class(stored.get()) == H5T_ENUM;
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 1 ||
      (H5Tget_class(stored.get()) != H5T_INTEGER && !c.real && !boolean)) {
    throw InputError(fmt::format("event file '{}': {} is not a 1-D array of {}", path, name,
                                 floats_allowed ? "integers or floats" : "integers"));
  }
  H5Sget_simple_extent_dims(space.get(), &c.n, nullptr);
  if (expected != static_cast<hsize_t>(-1) && c.n != expected) {
    throw InputError(fmt::format("event file '{}': {} has {} entries, {} {}", path, name, c.n, first, expected));
  }
  check_stored(c.d.get(), stored.get(), c.n, name, path, file_bytes);
  return c;
}

// Events read from a file in blocks of this many, straight into the recording.
constexpr hsize_t kBlock = hsize_t(1) << 18;
// Coordinates past this are refused: an image of the array would not fit memory.
constexpr std::int64_t kMostSide = 4096;

// Prophesee's HDF5 event file (Metavision): /CD/events, a 1-D compound dataset of x, y (uint16),
// p (int16) and t (int64, us), compressed with ECF. Read where this HDF5 can decode it (ECF's
// plugin on HDF5_PLUGIN_PATH, or a file written without it); the size is the events' span.
PolarityRecording read_metavision_cd(hid_t file, const std::string& path, std::uintmax_t file_bytes) {
  const char* name = "/CD/events";
  require_local(file, name, path, "/CD");
  Handle d(H5Dopen2(file, name, H5P_DEFAULT));
  Handle space(d.ok() ? H5Dget_space(d.get()) : H5I_INVALID_HID);
  Handle stored(d.ok() ? H5Dget_type(d.get()) : H5I_INVALID_HID);
  const bool compound = stored.ok() && H5Tget_class(stored.get()) == H5T_COMPOUND;
  const auto has = [&](const char* member) { return compound && H5Tget_member_index(stored.get(), member) >= 0; };
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 1 || !has("x") || !has("y") || !has("p") || !has("t")) {
    throw InputError(fmt::format("event file '{}': {} is not a 1-D array of events with fields x, y, p and t "
                                 "(Metavision's CD events)", path, name));
  }
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  check_stored(d.get(), stored.get(), n, name, path, file_bytes);
  ecf_refusal.clear();
  // ECF's decoder gives Metavision's 16-byte events, which the chunk's type must lay out so.
  Handle dcpl(H5Dget_create_plist(d.get()));
  unsigned flags = 0;
  std::size_t values = 0;
  if (dcpl.ok() && H5Pget_filter_by_id2(dcpl.get(), kEcfFilter, &flags, &values, nullptr, 0, nullptr, nullptr) >= 0) {
    const auto at = [&](const char* member) { return H5Tget_member_offset(stored.get(), static_cast<unsigned>(H5Tget_member_index(stored.get(), member))); };
    if (H5Tget_size(stored.get()) != kEcfEventBytes || at("x") != 0 || at("y") != 2 || at("p") != 4 || at("t") != 8) {
      throw InputError(fmt::format("event file '{}': {} is compressed with ECF, whose events are Metavision's 16 bytes (x, y, p "
                                   "and t at 0, 2, 4 and 8), but its type lays out {} bytes otherwise",
                                   path, name, H5Tget_size(stored.get())));
    }
  }
  // HDF5 converts each field, found by its name, to the memory's.
  struct Cd {
    std::int64_t x, y, p, t;
  };
  Handle memory_type(H5Tcreate(H5T_COMPOUND, sizeof(Cd)));
  H5Tinsert(memory_type.get(), "x", HOFFSET(Cd, x), H5T_NATIVE_INT64);
  H5Tinsert(memory_type.get(), "y", HOFFSET(Cd, y), H5T_NATIVE_INT64);
  H5Tinsert(memory_type.get(), "p", HOFFSET(Cd, p), H5T_NATIVE_INT64);
  H5Tinsert(memory_type.get(), "t", HOFFSET(Cd, t), H5T_NATIVE_INT64);
  PolarityRecording rec;
  rec.events.reserve(n);
  std::vector<Cd> block(std::min<hsize_t>(n, kBlock));
  for (hsize_t from = 0; from < n; from += kBlock) {
    hsize_t count = std::min(kBlock, n - from);
    Handle file_space(H5Dget_space(d.get()));
    Handle memory(H5Screate_simple(1, &count, nullptr));
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &from, nullptr, &count, nullptr) < 0 ||
        H5Dread(d.get(), memory_type.get(), memory.get(), file_space.get(), H5P_DEFAULT, block.data()) < 0) {
      throw InputError(fmt::format("event file '{}': cannot read {}{}", path, name,
                                   ecf_refusal.empty() ? "" : ": in the chunk from event " + std::to_string(from) + ", " + ecf_refusal));
    }
    for (hsize_t j = 0; j < count; ++j) {
      const Cd& e = block[j];
      if (e.x < 0 || e.y < 0 || e.x >= kMostSide || e.y >= kMostSide) {
        throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is outside 4096x4096", path, from + j, e.x, e.y));
      }
      rec.events.push_back({e.t, static_cast<std::int32_t>(e.x), static_cast<std::int32_t>(e.y), e.p != 0});
    }
  }
  return rec;
}

// An event table: a 2-D dataset of one row an event and four numeric columns, as v2e (`/events`:
// t in us, x, y, p 0/1, uint32) and MVSEC (`/davis/left/events`: x, y, t in s, p -1/1, float64)
// write them. `t_column` and `per_second` say where the stamp is and its unit.
struct EventTable {
  const char* name;
  const char* group;
  int x_column, y_column, t_column;
  double per_second;  // stamps a second: 1e6 for microseconds, 1 for seconds
};

PolarityRecording read_event_table(hid_t file, const EventTable& table, const std::string& path,
                                   std::uintmax_t file_bytes) {
  require_local(file, table.name, path, table.group);
  Handle d(H5Dopen2(file, table.name, H5P_DEFAULT));
  Handle space(d.ok() ? H5Dget_space(d.get()) : H5I_INVALID_HID);
  Handle stored(d.ok() ? H5Dget_type(d.get()) : H5I_INVALID_HID);
  hsize_t dims[2] = {0, 0};
  const H5T_class_t kind = stored.ok() ? H5Tget_class(stored.get()) : H5T_NO_CLASS;
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 2 ||
      H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0 || dims[1] != 4 ||
      (kind != H5T_INTEGER && kind != H5T_FLOAT)) {
    throw InputError(fmt::format("event file '{}': {} is not a table of numbers with four columns, one row an event",
                                 path, table.name));
  }
  const hsize_t n = dims[0];
  check_stored(d.get(), stored.get(), n * 4, table.name, path, file_bytes);
  PolarityRecording rec;
  rec.events.reserve(n);
  std::vector<double> block(std::min<hsize_t>(n, kBlock) * 4);
  for (hsize_t from = 0; from < n; from += kBlock) {
    const hsize_t start[2] = {from, 0}, count[2] = {std::min(kBlock, n - from), 4};
    Handle file_space(H5Dget_space(d.get()));
    Handle memory(H5Screate_simple(2, count, nullptr));
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr) < 0 ||
        H5Dread(d.get(), H5T_NATIVE_DOUBLE, memory.get(), file_space.get(), H5P_DEFAULT, block.data()) < 0) {
      throw InputError(fmt::format("event file '{}': cannot read {}", path, table.name));
    }
    for (hsize_t j = 0; j < count[0]; ++j) {
      const double* row = block.data() + 4 * j;
      const double x = row[table.x_column], y = row[table.y_column], t = row[table.t_column] * (1e6 / table.per_second);
      if (!(x >= 0 && y >= 0 && x < kMostSide && y < kMostSide) || x != std::floor(x) || y != std::floor(y)) {
        throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is not a pixel of a 4096x4096 array", path,
                                     from + j, x, y));
      }
      if (!(t >= 0 && t < 9e18)) {
        throw InputError(fmt::format("event file '{}': event {} has the stamp {} s", path, from + j,
                                     row[table.t_column] / table.per_second));
      }
      PolarityEvent e{std::llround(t), static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), row[3] > 0};
      rec.events.push_back(e);
    }
  }
  put_in_time_order(rec);
  return rec;
}

bool is_dataset(hid_t file, const char* name) {
  if (H5Lexists(file, name, H5P_DEFAULT) <= 0) return false;
  H5O_info_t info{};
  return H5Oget_info_by_name2(file, name, &info, H5O_INFO_BASIC, H5P_DEFAULT) >= 0 && info.type == H5O_TYPE_DATASET;
}

// Entries [from, from + count) of a column, converted by HDF5 to int64.
template <typename T>
void read_block(const Column& c, hsize_t from, hsize_t count, T* out, const char* name, const std::string& path) {
  Handle file_space(H5Dget_space(c.d.get()));
  Handle memory(H5Screate_simple(1, &count, nullptr));
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &from, nullptr, &count, nullptr) < 0 ||
      H5Dread(c.d.get(), type, memory.get(), file_space.get(), H5P_DEFAULT, out) < 0) {
    throw InputError(fmt::format("event file '{}': cannot read {}", path, name));
  }
}

// One root attribute "aesim.sensor.KEY" (a fixed-length string) into the map.
herr_t collect_sensor_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  const std::string key(name);
  if (key.rfind("aesim.sensor.", 0) != 0) return 0;
  Handle attr(H5Aopen(object, name, H5P_DEFAULT));
  Handle type(attr.ok() ? H5Aget_type(attr.get()) : H5I_INVALID_HID);
  if (!type.ok() || H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) return 0;
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > 4096) return 0;
  std::string value(size, '\0');
  if (H5Aread(attr.get(), type.get(), value.data()) < 0) return 0;
  value.resize(std::strlen(value.c_str()));
  (*static_cast<std::map<std::string, std::string>*>(data))[key.substr(13)] = value;
  return 0;
}

// Four columns x, y, t (integer microseconds, plus `t_offset`) and p (ON above 0), opened and
// checked, read in blocks straight into the events: memory is the events' own, not four columns
// more.
PolarityRecording read_columns(const Column (&columns)[4], const std::string (&names)[4], std::int64_t t_offset,
                               const std::string& path) {
  const hsize_t n = columns[0].n;
  PolarityRecording rec;
  rec.events.reserve(n);
  std::vector<std::int64_t> block[4];
  for (auto& b : block) b.resize(std::min<hsize_t>(n, kBlock));
  // Float stamps in an unnamed unit: a first pass over them says which (UnnamedStampUnit).
  std::vector<double> seconds;
  UnnamedStampUnit unnamed;
  if (columns[2].real) {
    seconds.resize(block[2].size());
    for (hsize_t from = 0; from < n && !unnamed.seconds; from += kBlock) {
      const hsize_t count = std::min(kBlock, n - from);
      read_block(columns[2], from, count, seconds.data(), names[2].c_str(), path);
      for (hsize_t j = 0; j < count; ++j) unnamed.see(seconds[j]);
    }
    rec.read_as.push_back(fmt::format("{} as floats in {}", names[2], unnamed.words()));
  }
  for (hsize_t from = 0; from < n; from += kBlock) {
    const hsize_t count = std::min(kBlock, n - from);
    for (int k = 0; k < 4; ++k) {
      if (k == 2 && columns[2].real) {
        read_block(columns[2], from, count, seconds.data(), names[2].c_str(), path);
        for (hsize_t j = 0; j < count; ++j) {
          const double us = seconds[j] * (unnamed.seconds ? 1e6 : 1);
          if (!(us >= 0 && us <= 1e18)) {
            throw InputError(fmt::format("event file '{}': event {} has time {}: not a time", path, from + j, seconds[j]));
          }
          block[2][j] = unnamed.microseconds(seconds[j]);
        }
        continue;
      }
      read_block(columns[k], from, count, block[k].data(), names[k].c_str(), path);
    }
    for (hsize_t j = 0; j < count; ++j) {
      const std::int64_t x = block[0][j], y = block[1][j];
      if (x < 0 || y < 0 || x >= kMostSide || y >= kMostSide) {
        throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is outside 4096x4096", path, from + j, x, y));
      }
      rec.events.push_back({block[2][j] + t_offset, static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), block[3][j] > 0});
    }
  }
  return rec;
}

// Names a column of events goes by in the field's files: M3ED's /prophesee/left/{x,y,t,p}, and
// anyone's group of the four.
constexpr const char* kStampNames[] = {"t", "ts", "timestamp", "timestamps"};
constexpr const char* kPolarityNames[] = {"p", "polarity", "pol", "polarities", "ps"};
// event_utils' (Stoffregen's, for E2VID and its kin): /events/xs, ys, ts (float seconds) and ps.
constexpr const char* kXNames[] = {"x", "xs"};
constexpr const char* kYNames[] = {"y", "ys"};
// A file's groups are searched up to this many objects (a file of millions of empty groups would
// otherwise take its time to say it holds no events).
constexpr std::size_t kMostObjectsSearched = 100000;

// The groups holding datasets x, y, a stamp and a polarity, in HDF5's name order (a stereo rig's
// left before its right), each with its four datasets' paths.
struct EventGroups {
  hid_t file;
  std::vector<std::array<std::string, 4>> found;
  std::vector<std::string> groups;
  std::size_t visited = 0;
};

std::string member(const std::string& group, const char* name) { return group == "." ? std::string("/") + name : "/" + group + "/" + name; }

herr_t collect_event_group(hid_t, const char* name, const H5O_info_t* info, void* data) {
  auto& search = *static_cast<EventGroups*>(data);
  if (++search.visited > kMostObjectsSearched) return 1;
  if (info->type != H5O_TYPE_GROUP) return 0;
  const auto first_of = [&](const auto& names) -> std::string {
    for (const char* n : names) {
      const std::string p = member(name, n);
      if (is_dataset(search.file, p.c_str())) return p;
    }
    return "";
  };
  const std::string x = first_of(kXNames), y = first_of(kYNames);
  const std::string t = first_of(kStampNames), p = first_of(kPolarityNames);
  if (x.empty() || y.empty() || t.empty() || p.empty()) return 0;
  search.found.push_back({x, y, t, p});
  search.groups.push_back(std::string(name) == "." ? "/" : "/" + std::string(name));
  return 0;
}

PolarityRecording read_in_this_process(const std::string& path) {
  quiet_hdf5();
  register_ecf_decoder();
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.ok()) throw InputError(fmt::format("event file '{}': HDF5 cannot open it", path));
  std::error_code ec;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  if (H5Lexists(file.get(), "events", H5P_DEFAULT) <= 0 && H5Lexists(file.get(), "CD", H5P_DEFAULT) > 0 &&
      H5Lexists(file.get(), "CD/events", H5P_DEFAULT) > 0) {
    return read_metavision_cd(file.get(), path, file_bytes);
  }
  if (is_dataset(file.get(), "events")) {
    return read_event_table(file.get(), {"/events", "/events", 1, 2, 0, 1e6}, path, file_bytes);
  }
  if (H5Lexists(file.get(), "events", H5P_DEFAULT) <= 0 && H5Lexists(file.get(), "davis", H5P_DEFAULT) > 0 &&
      H5Lexists(file.get(), "davis/left", H5P_DEFAULT) > 0 && is_dataset(file.get(), "davis/left/events")) {
    PolarityRecording rec =
        read_event_table(file.get(), {"/davis/left/events", "/davis/left", 0, 1, 2, 1}, path, file_bytes);
    if (H5Lexists(file.get(), "davis/right", H5P_DEFAULT) > 0 && is_dataset(file.get(), "davis/right/events")) {
      rec.notes.push_back("the right camera's events (/davis/right/events): the left camera's are read");
    }
    return rec;
  }
  if (H5Lexists(file.get(), "events", H5P_DEFAULT) <= 0 || !is_dataset(file.get(), "events/x")) {
    EventGroups search{file.get(), {}, {}, 0};
    H5Ovisit2(file.get(), H5_INDEX_NAME, H5_ITER_INC, collect_event_group, &search, H5O_INFO_BASIC);
    if (search.found.empty()) {
      throw InputError(fmt::format("event file '{}': no events (aesim reads /events/{{x,y,t,p}} as DSEC, /CD/events as "
                                   "Metavision, an /events table as v2e, /davis/left/events as MVSEC, or any group of "
                                   "datasets x, y, t and p, or event_utils' xs, ys, ts and ps)", path));
    }
    const std::array<std::string, 4>& chosen = search.found.front();
    const std::string names[] = {chosen[0], chosen[1], chosen[2], chosen[3]};
    Column columns[4];
    hsize_t n = static_cast<hsize_t>(-1);
    for (int k = 0; k < 4; ++k) {
      columns[k] = open_column(file.get(), names[k].c_str(), search.groups.front().c_str(), path, names[0].c_str(), n,
                               file_bytes, k == 2);
      n = columns[k].n;
    }
    PolarityRecording rec = read_columns(columns, names, 0, path);
    rec.read_as.insert(rec.read_as.begin(),
                       fmt::format("{}, {}, {}, {} ({}ON where the polarity is above 0)", names[0], names[1], names[2],
                                   names[3], columns[2].real ? "" : "stamps in microseconds, "));
    // event_utils' size, [height, width], beside its events.
    if (H5Aexists(file.get(), "sensor_resolution") > 0) {
      Handle attr(H5Aopen(file.get(), "sensor_resolution", H5P_DEFAULT));
      Handle space(attr.ok() ? H5Aget_space(attr.get()) : H5I_INVALID_HID);
      long long hw[2] = {0, 0};
      if (space.ok() && H5Sget_simple_extent_npoints(space.get()) == 2 &&
          H5Aread(attr.get(), H5T_NATIVE_LLONG, hw) >= 0 && hw[0] >= 1 && hw[1] >= 1 && hw[0] <= kMostSide &&
          hw[1] <= kMostSide) {
        rec.height = static_cast<int>(hw[0]);
        rec.width = static_cast<int>(hw[1]);
      }
    }
    for (std::size_t g = 1; g < search.groups.size(); ++g) {
      rec.notes.push_back(fmt::format("the events of {} ({}'s are read)", search.groups[g], search.groups.front()));
    }
    put_in_time_order(rec);
    return rec;
  }
  const std::string names[] = {"/events/x", "/events/y", "/events/t", "/events/p"};
  Column columns[4];
  hsize_t n = static_cast<hsize_t>(-1);
  for (int k = 0; k < 4; ++k) {
    columns[k] = open_column(file.get(), names[k].c_str(), "/events", path, names[0].c_str(), n, file_bytes);
    n = columns[k].n;
  }
  std::int64_t t_offset = 0;
  if (H5Lexists(file.get(), "t_offset", H5P_DEFAULT) > 0) {
    require_local(file.get(), "/t_offset", path);
    Handle d(H5Dopen2(file.get(), "t_offset", H5P_DEFAULT));
    Handle space(d.ok() ? H5Dget_space(d.get()) : H5I_INVALID_HID);
    if (!space.ok() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
        H5Dread(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &t_offset) < 0) {
      throw InputError(fmt::format("event file '{}': /t_offset is not one integer", path));
    }
  }
  PolarityRecording rec = read_columns(columns, names, t_offset, path);
  // aesim's own attributes, when aesim wrote the file.
  Handle events(H5Gopen2(file.get(), "events", H5P_DEFAULT));
  for (const char* name : {"width", "height"}) {
    if (!events.ok() || H5Aexists(events.get(), name) <= 0) continue;
    Handle attr(H5Aopen(events.get(), name, H5P_DEFAULT));
    long long v = 0;
    if (H5Aread(attr.get(), H5T_NATIVE_LLONG, &v) < 0 || v < 1 || v > 4096) {
      throw InputError(fmt::format("event file '{}': /events attribute {} is not a size from 1 to 4096", path, name));
    }
    (std::strcmp(name, "width") == 0 ? rec.width : rec.height) = static_cast<int>(v);
  }
  H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_sensor_attribute, &rec.sensor);
  return rec;
}

}  // namespace

PolarityRecording read_dsec_h5(const std::string& path) {
  require_input_file(path, "event file");
  {
    std::ifstream in(path, std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    if (std::memcmp(signature, "\x89HDF\r\n\x1a\n", 8) != 0) {
      throw InputError(fmt::format("event file '{}': not an HDF5 file", path));
    }
  }
  // HDF5 1.10 crashes on some corrupt files (a null dereference in its metadata cache, found by
  // tests/fuzz): it reads in a forked copy of aesim, and a crash there is this file's error.
  return read_in_forked_copy(path, "HDF5", [&path] { return read_in_this_process(path); });
}

}  // namespace aesim
