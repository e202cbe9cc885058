# The out-of-tree example (docs/examples/embed) as a user builds it: aesim installed into a fresh
# prefix, the example configured with find_package(aesim) against that prefix alone, built, run
# (its own receiver on tile 0, aesim::Receiver on tile 1's ports, the Imager's own on the others,
# no protocol violation: exit 0, and the wires traced);
# its events must equal the installed `aesim run --set sim.fidelity=cycle` on the same preset,
# scene, duration and seed, byte for byte.
# The same source is then built without CMake, from `pkg-config --cflags --libs aesim` of the
# prefix, and must give the same bytes. Both builds are C++20, as many projects are, where aesim
# and Debian's SystemC library are C++17: they link only with the SC_CPLUSPLUS that aesim::aesim
# and aesim.pc carry (cmake/aesimSystemCStandard.cmake); the sensor node's example stays C++17.
# Last, the Python module installed with them (when built: PYTHON is its interpreter, PYTHON_DIR
# its folder under the prefix) is imported from there and reads a preset only the prefix holds.
#   cmake -DBUILD=<aesim build> -DSOURCE=<aesim source> -DWORK=<scratch> -DGENERATOR=<gen>
#         -DCXX=<C++ compiler> [-DPYTHON=<python> -DPYTHON_DIR=<dir>] -P this
cmake_policy(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/required_definitions.cmake)
require_definitions(example_against_run BUILD SOURCE WORK GENERATOR CXX)
set(prefix ${WORK}/prefix)
set(scene ${SOURCE}/scenes/hdr/window.pfm)
set(duration 300ms)

include(${CMAKE_CURRENT_LIST_DIR}/installed_example.cmake)

build_installed_example(embed -DCMAKE_CXX_STANDARD=20)
execute_process(COMMAND ${WORK}/example/embed_example ${scene} ${duration} ${WORK}/waves
                OUTPUT_FILE ${WORK}/example.csv ERROR_VARIABLE said RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "embed_example failed (${status}): ${said}")
endif()
message(STATUS "${said}")
# The caller's trace file holds the tiles' wires, tile 1's (the bundled receiver's) among them.
file(STRINGS ${WORK}/waves.vcd scopes REGEX "^\\$scope module tile")
if(NOT "$scope module tile1 $end" IN_LIST scopes)
  message(FATAL_ERROR "the example's waves.vcd has no scope for tile 1: ${scopes}")
endif()
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

find_program(PKG_CONFIG pkg-config REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/lib/pkgconfig)
execute_process(COMMAND ${PKG_CONFIG} --cflags --libs aesim OUTPUT_VARIABLE flags RESULT_VARIABLE status
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "pkg-config finds no aesim in ${prefix}/lib/pkgconfig")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
run("building the example from pkg-config" ${CXX} -std=c++20 -O1 -o ${WORK}/pc_example
    ${SOURCE}/docs/examples/embed/embed_example.cpp ${flags} -Wl,-rpath,${prefix}/lib)
execute_process(COMMAND ${WORK}/pc_example ${scene} ${duration} OUTPUT_FILE ${WORK}/pc_example.csv
                RESULT_VARIABLE status ERROR_QUIET)
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/pc_example.csv ${WORK}/run.csv RESULT_VARIABLE differ)
if(NOT status EQUAL 0 OR NOT differ EQUAL 0)
  message(FATAL_ERROR "the example built from pkg-config failed (${status}) or differs from aesim run")
endif()
message(STATUS "built from pkg-config, the same rows")

# The library exports aesim's own names and SystemC's template instances, nothing of what it is
# built from (models/library/exports.map): a project's own Verilated receiver under the class
# name of aesim's, or its own Verilator or toml11, then never binds to aesim's copies.
find_program(NM nm REQUIRED)
find_program(CXXFILT c++filt REQUIRED)
find_program(GREP grep REQUIRED)
execute_process(COMMAND ${NM} -D --defined-only ${prefix}/lib/libaesim.so COMMAND ${CXXFILT}
                COMMAND ${GREP} -c "aesim::" OUTPUT_VARIABLE own OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND ${NM} -D --defined-only ${prefix}/lib/libaesim.so COMMAND ${CXXFILT}
                COMMAND ${GREP} -v -e "aesim::" -e "^[0-9a-f]* [A-Za-z] \\(typeinfo \\(name \\)\\?for \\|vtable for \\|guard variable for \\)\\?\\(sc_core\\|sc_dt\\|tlm\\|tlm_utils\\)::"
                OUTPUT_VARIABLE foreign)
if(own LESS 500 OR NOT foreign STREQUAL "")
  message(FATAL_ERROR "libaesim.so exports ${own} names of aesim's and these of others':\n${foreign}")
endif()
message(STATUS "libaesim.so exports ${own} names of aesim's, SystemC's template instances, nothing else")

if(PYTHON)
  file(WRITE ${prefix}/share/aesim/models/sensors/prefix_only.toml "base = \"aloha\"\n[pixel]\nc_int = \"77fF\"\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${prefix}/${PYTHON_DIR} ${PYTHON} -c
                          "import aesim; r = aesim.run(sensor='prefix_only', duration='10ms'); print(aesim.__file__, r.summary['sensor']['pixel']['c_int'])"
                  WORKING_DIRECTORY ${WORK} OUTPUT_VARIABLE said ERROR_VARIABLE err RESULT_VARIABLE status
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  string(FIND "${said}" "${prefix}/${PYTHON_DIR}/aesim" at)
  if(NOT status EQUAL 0 OR NOT at EQUAL 0 OR NOT said MATCHES "[.]so 7[.]7e-14$")
    message(FATAL_ERROR "the installed Python module (${prefix}/${PYTHON_DIR}) did not read the prefix's preset (${status}): ${said}${err}")
  endif()
  message(STATUS "the installed Python module reads the prefix's presets: ${said}")
endif()
