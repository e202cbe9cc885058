# The out-of-tree example (docs/examples/embed) as a user builds it: aesim installed into a fresh
# prefix, the example configured with find_package(aesim) against that prefix alone, built, run
# (its own receiver on tile 0, aesim's reference on the others, no protocol violation: exit 0);
# its events must equal the installed `aesim run --set sim.fidelity=cycle` on the same preset,
# scene, duration and seed, byte for byte.
#   cmake -DBUILD=<aesim build> -DSOURCE=<aesim source> -DWORK=<scratch> -DGENERATOR=<gen> -P this
foreach(v BUILD SOURCE WORK GENERATOR)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "example_against_run: -D${v}= is required")
  endif()
endforeach()
set(prefix ${WORK}/prefix)
set(scene ${SOURCE}/scenes/hdr/window.pfm)
set(duration 300ms)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK})
run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
run("configuring the example" ${CMAKE_COMMAND} -S ${SOURCE}/docs/examples/embed -B ${WORK}/example -G ${GENERATOR}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
run("building the example" ${CMAKE_COMMAND} --build ${WORK}/example)
execute_process(COMMAND ${WORK}/example/embed_example ${scene} ${duration}
                OUTPUT_FILE ${WORK}/example.csv ERROR_VARIABLE said RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "embed_example failed (${status}): ${said}")
endif()
message(STATUS "${said}")
run("aesim run" ${prefix}/bin/aesim run --scene ${scene} --set sim.fidelity=cycle --set sim.duration=${duration}
    --csv ${WORK}/run.csv)
file(STRINGS ${WORK}/example.csv rows)
list(LENGTH rows n)
if(n LESS 1000)
  message(FATAL_ERROR "the example delivered only ${n} rows: not the HDR scene's run")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/example.csv ${WORK}/run.csv RESULT_VARIABLE differ)
if(NOT differ EQUAL 0)
  message(FATAL_ERROR "the example's events differ from aesim run's (${WORK}/example.csv, ${WORK}/run.csv)")
endif()
message(STATUS "the example's ${n} rows equal aesim run's")
