#include "event_files/dsec_h5.hpp"

#include <cmath>
#include <cstring>
#include <fstream>

#include <fmt/format.h>
#include <hdf5.h>

#include "errors/input_error.hpp"
#include "event_files/event_stamps.hpp"
#include "files/input_path.hpp"

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

// HDF5 prints its own error stack unless told not to; aesim reports one line instead.
void quiet_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

Handle checked(hid_t id, const std::string& what) {
  if (id < 0) throw OutputError(what);
  return Handle(id);
}

Handle extendable(hid_t parent, const char* name, hid_t type) {
  const hsize_t zero = 0, unlimited = H5S_UNLIMITED, chunk = kDsecChunk;
  Handle space = checked(H5Screate_simple(1, &zero, &unlimited), "HDF5: cannot make a dataspace");
  Handle props = checked(H5Pcreate(H5P_DATASET_CREATE), "HDF5: cannot make dataset properties");
  H5Pset_chunk(props.get(), 1, &chunk);
  return checked(H5Dcreate2(parent, name, type, space.get(), H5P_DEFAULT, props.get(), H5P_DEFAULT),
                 fmt::format("HDF5: cannot create dataset {}", name));
}

void append(hid_t dataset, hid_t type, const void* data, hsize_t at, hsize_t count) {
  if (count == 0) return;
  const hsize_t size = at + count;
  if (H5Dset_extent(dataset, &size) < 0) throw OutputError("HDF5: cannot extend a dataset");
  Handle file_space = checked(H5Dget_space(dataset), "HDF5: no dataspace");
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &at, nullptr, &count, nullptr);
  Handle memory = checked(H5Screate_simple(1, &count, nullptr), "HDF5: cannot make a dataspace");
  if (H5Dwrite(dataset, type, memory.get(), file_space.get(), H5P_DEFAULT, data) < 0) {
    throw OutputError("HDF5: writing events failed (disk full?)");
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
  h_->file = checked(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                     fmt::format("cannot create HDF5 file '{}'", path));
  h_->events = checked(H5Gcreate2(h_->file.get(), "events", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
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
  append(h_->x.get(), H5T_NATIVE_UINT16, x_.data(), written_, n);
  append(h_->y.get(), H5T_NATIVE_UINT16, y_.data(), written_, n);
  append(h_->t.get(), H5T_NATIVE_UINT32, t_.data(), written_, n);
  append(h_->p.get(), H5T_NATIVE_UINT8, p_.data(), written_, n);
  written_ += n;
  x_.clear();
  y_.clear();
  t_.clear();
  p_.clear();
}

void DsecWriter::finish() {
  flush();
  while (ms_to_idx_.size() <= ms_total_) ms_to_idx_.push_back(count_);
  const hsize_t n = ms_to_idx_.size();
  Handle space = checked(H5Screate_simple(1, &n, nullptr), "HDF5: cannot make a dataspace");
  Handle index = checked(H5Dcreate2(h_->file.get(), "ms_to_idx", H5T_STD_U64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT,
                                    H5P_DEFAULT),
                         "HDF5: cannot create /ms_to_idx");
  if (H5Dwrite(index.get(), H5T_NATIVE_UINT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, ms_to_idx_.data()) < 0) {
    throw OutputError("HDF5: writing /ms_to_idx failed");
  }
  Handle scalar = checked(H5Screate(H5S_SCALAR), "HDF5: scalar space");
  Handle offset = checked(H5Dcreate2(h_->file.get(), "t_offset", H5T_STD_I64LE, scalar.get(), H5P_DEFAULT, H5P_DEFAULT,
                                     H5P_DEFAULT),
                          "HDF5: cannot create /t_offset");
  const long long zero = 0;
  H5Dwrite(offset.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, &zero);
  if (H5Fflush(h_->file.get(), H5F_SCOPE_GLOBAL) < 0) throw OutputError(fmt::format("HDF5: flushing '{}' failed", path_));
  h_ = std::make_unique<Handles>();  // the file is closed and complete
}

namespace {

// A whole 1-D dataset of integers, converted by HDF5 to `type` (a native type of T's width).
template <typename T>
std::vector<T> read_column(hid_t file, const char* name, hid_t type, const std::string& path, hsize_t* length) {
  Handle d(H5Dopen2(file, name, H5P_DEFAULT));
  if (!d.ok()) throw InputError(fmt::format("event file '{}': no dataset {} (not the DSEC layout)", path, name));
  Handle space(H5Dget_space(d.get()));
  Handle stored(H5Dget_type(d.get()));
  if (!space.ok() || H5Sget_simple_extent_ndims(space.get()) != 1 || H5Tget_class(stored.get()) != H5T_INTEGER) {
    throw InputError(fmt::format("event file '{}': {} is not a 1-D array of integers", path, name));
  }
  hsize_t n = 0;
  H5Sget_simple_extent_dims(space.get(), &n, nullptr);
  if (*length != static_cast<hsize_t>(-1) && n != *length) {
    throw InputError(fmt::format("event file '{}': {} has {} entries, /events/x {}", path, name, n, *length));
  }
  if (n > (hsize_t(1) << 32)) throw InputError(fmt::format("event file '{}': {} has more than 2^32 events", path, name));
  *length = n;
  std::vector<T> out(n);
  if (n > 0 && H5Dread(d.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0) {
    throw InputError(fmt::format("event file '{}': cannot read {}", path, name));
  }
  return out;
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

}  // namespace

PolarityRecording read_dsec_h5(const std::string& path) {
  if (!is_input_file(path, "event file")) throw InputError(fmt::format("event file '{}' not found", path));
  {
    std::ifstream in(path, std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    if (std::memcmp(signature, "\x89HDF\r\n\x1a\n", 8) != 0) {
      throw InputError(fmt::format("event file '{}': not an HDF5 file", path));
    }
  }
  quiet_hdf5();
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.ok()) throw InputError(fmt::format("event file '{}': HDF5 cannot open it", path));
  hsize_t n = static_cast<hsize_t>(-1);
  const auto x = read_column<std::int64_t>(file.get(), "/events/x", H5T_NATIVE_INT64, path, &n);
  const auto y = read_column<std::int64_t>(file.get(), "/events/y", H5T_NATIVE_INT64, path, &n);
  const auto t = read_column<std::int64_t>(file.get(), "/events/t", H5T_NATIVE_INT64, path, &n);
  const auto p = read_column<std::int64_t>(file.get(), "/events/p", H5T_NATIVE_INT64, path, &n);
  std::int64_t t_offset = 0;
  if (H5Lexists(file.get(), "t_offset", H5P_DEFAULT) > 0) {
    Handle d(H5Dopen2(file.get(), "t_offset", H5P_DEFAULT));
    Handle space(d.ok() ? H5Dget_space(d.get()) : H5I_INVALID_HID);
    if (!space.ok() || H5Sget_simple_extent_npoints(space.get()) != 1 ||
        H5Dread(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, &t_offset) < 0) {
      throw InputError(fmt::format("event file '{}': /t_offset is not one integer", path));
    }
  }
  PolarityRecording rec;
  rec.events.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (x[i] < 0 || y[i] < 0 || x[i] >= 4096 || y[i] >= 4096) {
      throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is outside 4096x4096", path, i, x[i], y[i]));
    }
    rec.events[i] = {t[i] + t_offset, static_cast<std::int32_t>(x[i]), static_cast<std::int32_t>(y[i]), p[i] != 0};
  }
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

}  // namespace aesim
