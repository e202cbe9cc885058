# The source paper's sensor node (docs/examples/sensor_node) as a user builds it: aesim installed into
# a fresh prefix, the example configured with find_package(aesim) against that prefix alone, built
# and run. Checked: on the rock sign (2 s at the aloha preset's light) the node decides "rock", loses
# nothing behind a 64-event FIFO at 57.6 MHz, and the approximately timed processor's row equals the
# loosely timed one's; at the cycle fidelity (each tile's aesim::Receiver streaming into the FIFO)
# it decides "rock" too; the letter C with the letters' templates decides "C"; a 1.8 MHz processor
# behind a 4-event FIFO loses events; the paper's inputs give 13.35 ms of processing; a bad option
# exits 2 with one line.
#   cmake -DBUILD=<aesim build> -DSOURCE=<aesim source> -DWORK=<scratch> -DGENERATOR=<gen> -P this
cmake_policy(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/required_definitions.cmake)
require_definitions(sensor_node_example BUILD SOURCE WORK GENERATOR)

include(${CMAKE_CURRENT_LIST_DIR}/installed_example.cmake)

# Runs the example; sets <var> to its CSV row as a list and <var>_said to its stderr.
set(columns sign fidelity timing fifo_depth clock_hz cycles_per_template duration_s events_delivered events_per_s
            decisions first_winner first_events_read first_decision_s first_recognition_ms first_lost events_read
            events_lost utilisation)
function(node var)
  execute_process(COMMAND ${WORK}/example/sensor_node ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE row
                  ERROR_VARIABLE said OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "sensor_node ${ARGN} failed (${status}): ${said}")
  endif()
  string(REPLACE "," ";" fields "${row}")
  list(LENGTH fields n)
  list(LENGTH columns want)
  if(NOT n EQUAL want)
    message(FATAL_ERROR "sensor_node ${ARGN}: a row of ${n} fields, not ${want}: ${row}")
  endif()
  foreach(i RANGE 0 17)
    list(GET columns ${i} name)
    list(GET fields ${i} value)
    set(${var}_${name} "${value}" PARENT_SCOPE)
  endforeach()
  set(${var} "${fields}" PARENT_SCOPE)
  set(${var}_said "${said}" PARENT_SCOPE)
endfunction()

build_installed_example(sensor_node)

node(loose --sign rock --set sim.duration=2s)
message(STATUS "${loose_said}")
if(NOT loose_first_winner STREQUAL "rock" OR loose_decisions LESS 2 OR NOT loose_events_lost EQUAL 0)
  message(FATAL_ERROR "loosely timed: winner '${loose_first_winner}', ${loose_decisions} decisions, ${loose_events_lost} lost")
endif()
if(NOT loose_events_read EQUAL loose_events_delivered)
  message(FATAL_ERROR "the processor read ${loose_events_read} of ${loose_events_delivered} events and lost none")
endif()
if(NOT loose_said MATCHES "the paper's inputs \\(1281.8 events x 6 templates x 100 cycles at 57.6 MHz\\): 13.35 ms")
  message(FATAL_ERROR "the paper's processing time is not 13.35 ms: ${loose_said}")
endif()

node(approximate --sign rock --set sim.duration=2s --timing approximate)
list(REMOVE_AT loose 2)
list(REMOVE_AT approximate 2)
if(NOT loose STREQUAL approximate)
  message(FATAL_ERROR "approximately timed differs from loosely timed:\n${approximate}\n${loose}")
endif()

node(cycle --sign rock --set sim.duration=500ms --fidelity cycle)
if(NOT cycle_first_winner STREQUAL "rock" OR cycle_events_delivered LESS 3000)
  message(FATAL_ERROR "cycle fidelity: winner '${cycle_first_winner}' after ${cycle_events_delivered} events")
endif()

node(lossy --sign rock --set sim.duration=2s --clock 1.8e6 --fifo 4)
if(lossy_events_lost LESS 1000 OR NOT lossy_events_read LESS lossy_events_delivered)
  message(FATAL_ERROR "a 1.8 MHz processor behind 4 events lost only ${lossy_events_lost}")
endif()

# Another scene and other templates: the letter C among the letters' templates.
node(letter --scene ${SOURCE}/scenes/letters/C.pgm --templates ${SOURCE}/scenes/templates/letters --set sim.duration=1s)
if(NOT letter_first_winner STREQUAL "C")
  message(FATAL_ERROR "the letter C was taken for '${letter_first_winner}'")
endif()

execute_process(COMMAND ${WORK}/example/sensor_node --fifo 2.5 RESULT_VARIABLE status OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "^sensor_node: --fifo: '2.5' is not a whole number of events\n$" OR NOT out STREQUAL "")
  message(FATAL_ERROR "a bad --fifo gave exit ${status}, stdout '${out}', stderr '${err}'")
endif()
message(STATUS "the sensor node example: rock recognised at both timings and both fidelities; losses when too slow")
