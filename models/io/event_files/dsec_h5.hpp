#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "aesim/event_files/aedat4.hpp"
#include "aesim/event_files/event_stamps.hpp"
#include "aesim/event_files/event_writer.hpp"

namespace aesim {

// HDF5 in the DSEC layout: /events/x and /events/y (uint16), /events/t (uint32, us after
// /t_offset), /events/p (uint8: 1 for a normal event, 0 for a ghost), /t_offset (int64, us, 0
// here) and /ms_to_idx (uint64: entry k is the index of the first event at or after k ms; one
// entry per millisecond of the run and one past its end). Uncompressed, chunked, appended as the
// run goes. aesim adds attributes DSEC does not have: /events width and height, and the sensor
// parameters on the root as "aesim.sensor.KEY" strings. `path` is a file the writer owns.
class DsecWriter : public EventFileWriter {
 public:
  DsecWriter(const std::string& path, const EventFileSpec& spec, double duration_s);
  ~DsecWriter() override;
  void events(const AddressEvent* first, std::size_t count) override;
  void finish() override;
  // With no events: DSEC's EventSlicer reads the last stamp when it opens a file, so it cannot open
  // this one (h5py and aesim can).
  std::string reader_warning() const override;

 private:
  void flush();
  struct Handles;
  std::unique_ptr<Handles> h_;
  std::string path_;
  MicrosecondStamps stamps_;
  std::uint64_t ms_total_;
  std::uint64_t written_ = 0, count_ = 0;
  std::vector<std::uint16_t> x_, y_;
  std::vector<std::uint32_t> t_;
  std::vector<std::uint8_t> p_;
  std::vector<std::uint64_t> ms_to_idx_;
};

// Reads /events/{x,y,t,p} (and /t_offset when present) of a DSEC-layout file, the /CD/events
// compound (x, y, p, t) of a Metavision HDF5 event file where this HDF5 decodes its compression,
// v2e's /events table (one row an event: t in us, x, y, p 0/1) or MVSEC's /davis/left/events
// table (x, y, t in s, p -1/1; the right camera's is left and noted). A table's events stamped
// before the row above's are put in time order and counted. Throws InputError.
PolarityRecording read_dsec_h5(const std::string& path);

}  // namespace aesim
