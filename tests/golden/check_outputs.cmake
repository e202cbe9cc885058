# Golden outputs: each scenario below runs `aesim run` and hashes what it wrote; the hashes must
# equal tests/golden/outputs.sha256. The scenarios cover every rung (queue, event, cycle with the
# reference model and with the RTL, pixel_processes, fixed_step), every event file format and
# layout, still and moving scenes, shot noise and collisions, so that work on speed cannot change
# a byte unnoticed. A change meant to change outputs regenerates the file
# (cmake -DAESIM=... -DSOURCE=... -DWORK=... -DUPDATE=ON -P check_outputs.cmake) and says why in
# its commit.
#   -DAESIM=the aesim program  -DSOURCE=the source tree  -DWORK=a scratch folder
cmake_minimum_required(VERSION 3.20)
set(golden ${SOURCE}/tests/golden/outputs.sha256)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(letter "--scene ${SOURCE}/scenes/letters/A.pgm")
set(moving "--scene ${SOURCE}/scenes/moving_disc --duration 1s")
set(qcif "--set array.rows=144 --set array.cols=176 --scene ${SOURCE}/scenes/uniform.pgm")
# name | arguments, split as a shell would (outputs named NAME*.EXT in WORK)
set(scenarios
  "event_letter|${letter} --duration 1s --out event_letter.aedat --csv event_letter.csv --truth event_letter_truth.csv --recon event_letter.pgm --summary event_letter.json"
  "event_letter_davis|${letter} --duration 1s --out event_letter_davis.aedat --aedat-layout davis"
  "event_letter_lz4|${letter} --duration 1s --out event_letter_lz4.aedat4"
  "event_letter_plain|${letter} --duration 1s --out event_letter_plain.aedat4 --aedat4-compression none"
  "event_letter_npy|${letter} --duration 1s --out event_letter_npy.npy"
  "event_letter_h5|${letter} --duration 1s --out event_letter_h5.h5"
  "event_letter_raw|${letter} --duration 1s --out event_letter_raw.raw"
  "event_letter_raw3|${letter} --duration 1s --out event_letter_raw3.raw --raw-encoding evt3"
  "event_letter_dat|${letter} --duration 1s --out event_letter_dat.dat"
  "queue_letter|${letter} --duration 1s --set sim.fidelity=queue --csv queue_letter.csv"
  "cycle_hdr|--scene ${SOURCE}/scenes/hdr/window.pfm --duration 300ms --set sim.fidelity=cycle --set bus.t_event=2us --set receiver.clock=5MHz --csv cycle_hdr.csv --truth cycle_hdr_truth.csv"
  "cycle_rtl|${letter} --duration 200ms --set sim.fidelity=cycle --set receiver.model=rtl --csv cycle_rtl.csv"
  "processes_letter|${letter} --duration 200ms --set sim.fidelity=pixel_processes --csv processes_letter.csv"
  "fixed_step_letter|${letter} --duration 200ms --set sim.fidelity=fixed_step --csv fixed_step_letter.csv"
  "aloha_hdr|--scene ${SOURCE}/scenes/hdr/window.pfm --duration 1s --set bus.t_event=2us --csv aloha_hdr.csv --truth aloha_hdr_truth.csv"
  "moving_held_shot|${moving} --set pixel.shot_noise=true --set pixel.initial=random --csv moving_held_shot.csv"
  "moving_looped|${moving} --set scene.frame_rate=100Hz --set scene.loop=true --set pixel.i_max=100pA --out moving_looped.aedat"
  "moving_looped_shot|${moving} --set scene.frame_rate=100Hz --set scene.loop=true --set pixel.i_max=100pA --set pixel.shot_noise=true --out moving_looped_shot.aedat"
  "qcif_shot|${qcif} --duration 200ms --set pixel.i_max=100pA --set pixel.shot_noise=true --set sim.threads=2 --out qcif_shot.aedat"
  "qcif_still|${qcif} --duration 200ms --set pixel.i_max=100pA --set sim.threads=2 --out qcif_still.npy"
)
set(lines "")
foreach(scenario ${scenarios})
  string(FIND "${scenario}" "|" bar)
  string(SUBSTRING "${scenario}" 0 ${bar} name)
  math(EXPR from "${bar} + 1")
  string(SUBSTRING "${scenario}" ${from} -1 line)
  separate_arguments(args UNIX_COMMAND "${line}")
  execute_process(COMMAND ${AESIM} run ${args} WORKING_DIRECTORY ${WORK}
                  RESULT_VARIABLE status OUTPUT_QUIET ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "golden scenario ${name}: aesim run failed (${status}): ${err}")
  endif()
  file(GLOB outputs RELATIVE ${WORK} ${WORK}/${name}*)
  list(SORT outputs)
  foreach(output ${outputs})
    if(output MATCHES "\\.json$")
      # The summary names the wall time, which no two runs share: its other fields are compared.
      file(READ ${WORK}/${output} text)
      string(REGEX REPLACE "\"wall_time_s\": *[0-9.eE+-]+" "\"wall_time_s\": 0" text "${text}")
      string(SHA256 hash "${text}")
    else()
      file(SHA256 ${WORK}/${output} hash)
    endif()
    string(APPEND lines "${hash}  ${output}\n")
  endforeach()
endforeach()
if(UPDATE)
  file(WRITE ${golden} "${lines}")
  message(STATUS "wrote ${golden}")
  return()
endif()
file(READ ${golden} expected)
if(NOT expected STREQUAL lines)
  file(WRITE ${WORK}/outputs.sha256 "${lines}")
  execute_process(COMMAND diff ${golden} ${WORK}/outputs.sha256 OUTPUT_VARIABLE difference)
  message(FATAL_ERROR "outputs differ from the golden hashes (- golden, + now; files in ${WORK}):\n${difference}")
endif()
