#pragma once
#include <string>

#include "aesim/event_files/aedat4.hpp"

namespace aesim {

// Whether `data` starts as an AEDAT 3.1 file does ("#!AER-DAT3.1").
bool is_aedat31(const std::string& data);

// The polarity events of an AEDAT 3.1 file (cAER, DV's predecessor, and jAER write it): an ASCII
// header up to the line "#!END-HEADER" (CRLF, or LF as some writers end it), then event packets, each a 28-byte little-endian header
// (eventType, eventSource, eventSize, eventTSOffset, eventTSOverflow, eventCapacity, eventNumber,
// eventValid) and eventCapacity events of eventSize bytes. A polarity event (type 1, 8 bytes) is
// a 32-bit word (bit 0 valid, bit 1 polarity, y in bits 2-16, x in 17-31) and a 32-bit stamp in
// microseconds, extended by the packet's eventTSOverflow (x 2^31). Events not marked valid are
// left out and counted (`invalid`); packets of other types are skipped and counted. Nothing is read past the bytes given:
// a packet that claims more is an InputError naming `label`, as is anything else malformed.
PolarityRecording decode_aedat31(const std::string& data, const std::string& label);

}  // namespace aesim
