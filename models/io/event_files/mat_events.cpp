#include "aesim/event_files/mat_events.hpp"

#include <matio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "aesim/errors/input_error.hpp"
#include "aesim/event_files/forked_reader.hpp"
#include "aesim/files/input_path.hpp"
#include "aesim/limits/limits.hpp"

namespace aesim {
namespace {

constexpr double kSidesUpTo = 4096;  // a pixel of a 4096x4096 array at most
// Numbers a byte of the file can hold at most: deflate (MATLAB's version 5 and 7.3 compression)
// expands a byte to at most 1032. A vector claiming more than that is refused before matio reads
// it: an HDF5 dataset's unwritten chunks would otherwise be read as fill, work the file's bytes
// never paid for.
constexpr std::uintmax_t kMostPerByte = 1032;

// The names each vector goes by, first the usual one.
constexpr std::array<const char*, 1> kX = {"x"};
constexpr std::array<const char*, 1> kY = {"y"};
constexpr std::array<const char*, 3> kT = {"ts", "t", "timestamp"};
constexpr std::array<const char*, 3> kP = {"pol", "p", "polarity"};

// matio's last complaint, for the error it ends in (the reader runs in a copy of its own).
std::string& matio_message() {
  static std::string message;
  return message;
}
void on_matio_log(int level, char* message) {
  if (level <= MATIO_LOG_LEVEL_CRITICAL && message != nullptr && matio_message().empty()) matio_message() = message;
}

struct MatCloser {
  void operator()(mat_t* m) const { Mat_Close(m); }
};
struct VarFree {
  void operator()(matvar_t* v) const { Mat_VarFree(v); }
};
using Var = std::unique_ptr<matvar_t, VarFree>;

std::size_t elements(const matvar_t* v) {
  std::size_t n = 1;
  for (int d = 0; d < v->rank; ++d) n *= v->dims[d];
  return n;
}

// A vector's numbers, from a variable whose data matio has read.
std::vector<double> numbers(const matvar_t* v, const std::string& name, const std::string& path) {
  const auto fail = [&](const std::string& why) {
    throw InputError(fmt::format("event file '{}': {} is {}", path, name, why));
  };
  if (v->isComplex) fail("complex");
  std::size_t longest = 0;
  for (int d = 0; d < v->rank; ++d) {
    if (v->dims[d] != 1 && longest > 1) fail("not a vector");
    longest = std::max(longest, v->dims[d]);
  }
  const std::size_t n = elements(v);
  std::vector<double> out(n);
  if (n == 0) return out;
  if (v->data == nullptr) fail("not read (matio gave no data)");
  const auto copy = [&](auto type_tag) {
    using T = decltype(type_tag);
    if (v->data_size != static_cast<int>(sizeof(T)) && v->data_size != 0) fail("stored in a type its class does not name");
    const auto* p = static_cast<const T*>(v->data);
    for (std::size_t i = 0; i < n; ++i) out[i] = static_cast<double>(p[i]);
  };
  switch (v->class_type) {
    case MAT_C_DOUBLE: copy(double{}); break;
    case MAT_C_SINGLE: copy(float{}); break;
    case MAT_C_INT8: copy(std::int8_t{}); break;
    case MAT_C_UINT8: copy(std::uint8_t{}); break;
    case MAT_C_INT16: copy(std::int16_t{}); break;
    case MAT_C_UINT16: copy(std::uint16_t{}); break;
    case MAT_C_INT32: copy(std::int32_t{}); break;
    case MAT_C_UINT32: copy(std::uint32_t{}); break;
    case MAT_C_INT64: copy(std::int64_t{}); break;
    case MAT_C_UINT64: copy(std::uint64_t{}); break;
    case MAT_C_SPARSE: fail("a sparse matrix"); break;
    default: fail(fmt::format("not numbers (MATLAB class {})", static_cast<int>(v->class_type)));
  }
  return out;
}

// The first of `names` a lookup finds, or null.
template <std::size_t N, typename Find>
const char* first_found(const std::array<const char*, N>& names, Find find) {
  for (const char* name : names) {
    if (find(name)) return name;
  }
  return nullptr;
}

// The four vectors' names where they are (top level, or the fields of one struct).
struct Where {
  std::string structure;  // empty: variables of their own
  const char *x = nullptr, *y = nullptr, *t = nullptr, *p = nullptr;
  bool complete() const { return x && y && t && p; }
};

template <typename Find>
Where look(Find find) {
  Where w;
  w.x = first_found(kX, find);
  w.y = first_found(kY, find);
  w.t = first_found(kT, find);
  w.p = first_found(kP, find);
  return w;
}

PolarityRecording read_in_this_process(const std::string& path) {
  Mat_LogInitFunc("aesim", on_matio_log);
  const std::unique_ptr<mat_t, MatCloser> mat(Mat_Open(path.c_str(), MAT_ACC_RDONLY));
  if (!mat) {
    throw InputError(fmt::format("event file '{}': not a MATLAB file matio reads{}", path,
                                 matio_message().empty() ? "" : " (" + matio_message() + ")"));
  }
  // The variables, their shapes only.
  std::vector<std::string> names, described;
  std::vector<std::string> structures;
  std::vector<std::vector<std::string>> fields;
  while (Var info{Mat_VarReadNextInfo(mat.get())}) {
    if (info->name == nullptr) continue;
    names.emplace_back(info->name);
    std::string shape;
    for (int d = 0; d < info->rank; ++d) shape += fmt::format("{}{}", d ? "x" : "", info->dims[d]);
    described.push_back(fmt::format("{} ({})", info->name, shape));
    if (names.size() > 10000) throw InputError(fmt::format("event file '{}': more than 10000 variables", path));
    if (info->class_type == MAT_C_STRUCT && elements(info.get()) == 1) {
      structures.emplace_back(info->name);
      std::vector<std::string> own;
      const unsigned n = Mat_VarGetNumberOfFields(info.get());
      char* const* field_names = Mat_VarGetStructFieldnames(info.get());
      for (unsigned f = 0; field_names != nullptr && f < n; ++f) own.emplace_back(field_names[f]);
      fields.push_back(own);
    }
  }
  const auto has = [](const std::vector<std::string>& in) {
    return [&in](const char* name) { return std::find(in.begin(), in.end(), name) != in.end(); };
  };
  Where where = look(has(names));
  for (std::size_t s = 0; !where.complete() && s < structures.size(); ++s) {
    where = look(has(fields[s]));
    where.structure = structures[s];
  }
  if (!where.complete()) {
    std::string held;
    for (const std::string& d : described) held += (held.empty() ? "" : ", ") + d;
    throw InputError(fmt::format("event file '{}': no vectors x, y, ts (or t) and pol (or p), as variables or the fields "
                                 "of a struct (it holds {})",
                                 path, held.empty() ? "no variables" : held));
  }
  // The vectors' numbers, each first bounded by its length and by the file's bytes.
  std::error_code size_error;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, size_error);
  const auto bound = [&](const matvar_t* info, const std::string& name) {
    const std::size_t n = info != nullptr ? elements(info) : 0;
    if (n > kMaxExpandedEvents) {
      throw InputError(fmt::format("event file '{}': {} holds more than the {} events aesim reads from one file", path, name,
                                   kMaxExpandedEvents));
    }
    if (!size_error && n > kMostPerByte * file_bytes) {
      throw InputError(fmt::format("event file '{}': {} claims {} numbers, more than its {} bytes hold even deflated", path,
                                   name, n, file_bytes));
    }
  };
  std::vector<double> column[4];
  const char* const which[4] = {where.x, where.y, where.t, where.p};
  const auto named = [&](const char* name) { return where.structure.empty() ? std::string(name) : where.structure + "." + name; };
  if (where.structure.empty()) {
    for (int c = 0; c < 4; ++c) {
      const Var info{Mat_VarReadInfo(mat.get(), which[c])};
      bound(info.get(), which[c]);
      const Var v{Mat_VarRead(mat.get(), which[c])};
      if (!v) throw InputError(fmt::format("event file '{}': {} does not read ({})", path, which[c], matio_message()));
      column[c] = numbers(v.get(), named(which[c]), path);
    }
  } else {
    const Var info{Mat_VarReadInfo(mat.get(), where.structure.c_str())};
    for (int c = 0; info && c < 4; ++c) {
      bound(Mat_VarGetStructFieldByName(info.get(), which[c], 0), named(which[c]));
    }
    const Var v{Mat_VarRead(mat.get(), where.structure.c_str())};
    if (!v) throw InputError(fmt::format("event file '{}': {} does not read ({})", path, where.structure, matio_message()));
    for (int c = 0; c < 4; ++c) {
      const matvar_t* f = Mat_VarGetStructFieldByName(v.get(), which[c], 0);
      if (f == nullptr) throw InputError(fmt::format("event file '{}': {} does not read", path, named(which[c])));
      column[c] = numbers(f, named(which[c]), path);
    }
  }
  const std::size_t n = column[0].size();
  for (int c = 1; c < 4; ++c) {
    if (column[c].size() != n) {
      throw InputError(fmt::format("event file '{}': {} holds {} numbers where {} holds {}", path, named(which[c]),
                                   column[c].size(), named(which[0]), n));
    }
  }
  // The convention, from the polarities: 0/1 or -1/1, or MATLAB's 1/2 (indices from 1).
  bool zero_based = true, two_seen = false;
  for (std::size_t i = 0; i < n; ++i) {
    const double p = column[3][i];
    if (p == 2) two_seen = true;
    if (p != -1 && p != 0 && p != 1 && p != 2) {
      throw InputError(fmt::format("event file '{}': event {} has the polarity {} (aesim reads 0/1, -1/1 or MATLAB's 1/2)",
                                   path, i, p));
    }
  }
  if (two_seen) {
    for (std::size_t i = 0; i < n; ++i) {
      if (column[3][i] < 1) {
        throw InputError(fmt::format("event file '{}': polarities of 2 and of {} (aesim reads 0/1, -1/1 or MATLAB's 1/2)",
                                     path, column[3][i]));
      }
    }
    zero_based = false;
  }
  const double shift = zero_based ? 0 : 1;
  bool seconds = false;
  for (const double t : column[2]) {
    if (t != std::floor(t)) seconds = true;
  }
  PolarityRecording rec;
  rec.events.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = column[0][i] - shift, y = column[1][i] - shift;
    if (!(x >= 0 && y >= 0 && x < kSidesUpTo && y < kSidesUpTo) || x != std::floor(x) || y != std::floor(y)) {
      throw InputError(fmt::format("event file '{}': event {} at ({}, {}) is not a pixel of a 4096x4096 array{}", path, i,
                                   column[0][i], column[1][i], zero_based ? "" : " (MATLAB's indices, from 1)"));
    }
    const double t = seconds ? column[2][i] * 1e6 : column[2][i];
    if (!(t >= 0 && t < 9e18)) throw InputError(fmt::format("event file '{}': event {} has the stamp {}", path, i, column[2][i]));
    rec.events.push_back({std::llround(t), static_cast<std::int32_t>(x), static_cast<std::int32_t>(y),
                          zero_based ? column[3][i] > 0 : column[3][i] == 2});
  }
  if (!zero_based) {
    rec.read_as.push_back(fmt::format("{} counting from 1, as MATLAB does: x and y one less, polarity 2 ON and 1 OFF",
                                      where.structure.empty() ? std::string("the file's vectors") : where.structure));
  }
  if (seconds) rec.read_as.push_back(fmt::format("seconds: {} has fractions", named(which[2])));
  put_in_time_order(rec);
  return rec;
}

}  // namespace

PolarityRecording read_mat_events(const std::string& path) {
  require_input_file(path, "event file");
  // matio, like HDF5, may crash on a hostile file: it reads in a forked copy of aesim.
  return read_in_forked_copy(path, "matio", [&path] { return read_in_this_process(path); });
}

}  // namespace aesim
