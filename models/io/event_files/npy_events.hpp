#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "aesim/containers/uninitialized_growth.hpp"
#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/event_writer.hpp"
#include "aesim/output/space_ahead.hpp"

namespace aesim {

// NumPy .npy (format 1.0) holding a 1-D structured array with tonic's event dtype: x int16,
// y int16, t int64 (us), p bool (1 for a normal event, 0 for a ghost), packed (13 bytes a record).
// The record count is known only at the end, so the header reserves room for it and finish()
// writes it: `path` is a file the writer owns (a temporary of OutputFiles).
class NpyWriter : public EventFileWriter {
 public:
  NpyWriter(const std::string& path, double tick);
  ~NpyWriter() override;
  NpyWriter(const NpyWriter&) = delete;
  NpyWriter& operator=(const NpyWriter&) = delete;
  void events(const AddressEvent* first, std::size_t count) override;
  void finish() override;

 private:
  void flush();
  // All of `n` bytes at `offset`, or OutputError with the system's reason.
  void write_at(const char* data, std::size_t n, std::uint64_t offset);
  int fd_;
  std::string path_;
  MicrosecondStamps stamps_;
  std::uint64_t count_ = 0;
  std::uint64_t written_ = 0;  // bytes of the file written
  SpaceAhead space_;
  // Grown by each batch's records and written over at once: no zeros written first.
  UninitializedGrowthVector<char> buffer_;
};

// Reads a .npy structured array with fields x, y, t (integers) and p (bool or integer, ON above
// 0: 1 or True, not 0, False or -1), in any order and little-endian widths; the file records no
// array size. Throws InputError naming `label`.
PolarityRecording decode_npy(const std::string& data, const std::string& label);

}  // namespace aesim
