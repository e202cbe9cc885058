#pragma once
// aesim for a SystemC project: `#include <aesim/aesim.hpp>` and link aesim::aesim
// (find_package(aesim)). What it offers, in docs/embedding.md:
//   - Imager: the imager at the cycle fidelity as a module in the caller's own sc_main;
//   - EventSource: the event fidelity's events handed over at their times, into an sc_fifo;
//   - EventFifoTarget: a memory-mapped event FIFO with an interrupt behind a TLM-2.0 socket;
//   - simulate(): a whole run at any fidelity, in a SystemC context of its own;
//   - the configuration (presets, --set keys), scenes, the record of a run, event files.
#include "aesim/version.hpp"
#include "config/sensor_config.hpp"
#include "embed/event_fifo_target.hpp"
#include "embed/event_source.hpp"
#include "embed/imager.hpp"
#include "errors/input_error.hpp"
#include "event_files/event_file.hpp"
#include "event_files/events_csv.hpp"
#include "events/address_event.hpp"
#include "events/event_log.hpp"
#include "receiver/receiver_module.hpp"
#include "receiver/receiver_signals.hpp"
#include "run/imager_simulation.hpp"
#include "scene/photocurrents.hpp"
#include "scene/scene.hpp"
