#pragma once
// aesim for a SystemC project: `#include <aesim/aesim.hpp>` and link aesim::aesim
// (find_package(aesim)). What it offers, in docs/embedding.md:
//   - Imager: the imager at the cycle fidelity as a module in the caller's own sc_main;
//   - Receiver: aesim's bundled receiver (the reference model of rtl/aer_receiver.v) with ports;
//   - EventSource: the event fidelity's events handed over at their times, into an sc_fifo;
//   - EventFifoTarget: a memory-mapped event FIFO with an interrupt behind a TLM-2.0 socket, fed by
//     the event fidelity's timed stream or (ReceiverStreamFeed) a tile's receiver at the cycle one;
//   - NodeProcessor: the source paper's sensor node processor, running its recogniser as timed
//     firmware against that FIFO (loosely or approximately timed); templates and the recogniser;
//   - run_sensor(): a whole run as `aesim run` makes it (outputs, summary, warnings returned);
//   - simulate(): a run's simulation alone, at any fidelity, in a SystemC context of its own;
//   - the configuration (presets, --set keys), scenes, the record of a run, event files, and
//     data_dir(): where the shipped presets, scenes and templates are.
#include "aesim/version.hpp"
#include "aesim/config/sensor_config.hpp"
#include "aesim/embed/event_fifo_target.hpp"
#include "aesim/embed/event_source.hpp"
#include "aesim/embed/imager.hpp"
#include "aesim/embed/receiver_stream_feed.hpp"
#include "aesim/errors/input_error.hpp"
#include "aesim/files/data_dir.hpp"
#include "aesim/event_files/event_file.hpp"
#include "aesim/event_files/events_csv.hpp"
#include "aesim/events/address_event.hpp"
#include "aesim/events/event_log.hpp"
#include "aesim/receiver/receiver.hpp"
#include "aesim/receiver/receiver_module.hpp"
#include "aesim/receiver/receiver_signals.hpp"
#include "aesim/run/imager_simulation.hpp"
#include "aesim/scene/photocurrents.hpp"
#include "aesim/scene/scene.hpp"
#include "aesim/sensor_run/sensor_run.hpp"
#include "aesim/classify/template_classifier.hpp"
#include "aesim/sensor_node/node_processor.hpp"
