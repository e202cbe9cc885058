#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// An EVIMO2 (v2) sequence's folder, as EVIMO's ground-truth-format page lays it out and pydvs's
// evimo-gen.py writes it: dataset_events_t.npy (each event's stamp in seconds, N or N x 1),
// dataset_events_xy.npy (N x 2: x, y) and dataset_events_p.npy (N or N x 1), beside the sequence's
// depth, masks, frames and dataset_info.npz (not read). No array size is recorded: the events'
// span, or --size. Throws InputError naming the folder and the file.
bool is_evimo2_folder(const std::string& path);
PolarityRecording read_evimo2_folder(const std::string& path);

}  // namespace aesim
