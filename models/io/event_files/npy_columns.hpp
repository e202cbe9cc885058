#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// The numbers of one column of a .npy array, as doubles (whole numbers past 2^53 are not stamps),
// and whether they were floats.
struct NpyNumbers {
  std::vector<double> values;
  bool floating = false;
};

// Column `column` of an array of `columns` numbers an event (N x columns, in C or Fortran order),
// or, for one column, an array of N or N x 1: integers, floats of 4 or 8 bytes or bools, either
// byte order. Throws InputError("<what>: <reason>").
NpyNumbers read_npy_numbers(const std::string& npy, const std::string& what, std::uint64_t column = 0,
                            std::uint64_t columns = 1);

// The events whose x, y, stamp and polarity are the four columns (of one length each): stamps in
// seconds (rounded to the microsecond) when `seconds`, else whole microseconds; ON where the
// polarity is above 0. `names` are the columns' (x, y, t, p), for messages; every event must name a
// pixel of a 4096x4096 array. Throws InputError naming `label`.
PolarityRecording events_from_columns(const NpyNumbers& x, const NpyNumbers& y, const NpyNumbers& t, const NpyNumbers& p,
                                      bool seconds, const std::array<std::string, 4>& names, const std::string& label);

}  // namespace aesim
