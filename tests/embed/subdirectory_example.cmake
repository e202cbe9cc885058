# docs/examples/subdirectory as a user's project configures it: aesim's source added with
# add_subdirectory, aesim::aesim found, none of aesim's tests in the project's CTest (its own one only), and the
# example's source compiled against the headers as the project sees them (the library itself is
# built by embed.find_package_example's install; building it again here would double its time).
#   cmake -DSOURCE=<aesim source> -DWORK=<scratch> -DGENERATOR=<gen> -DCXX=<compiler> -P this
cmake_policy(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/required_definitions.cmake)
require_definitions(subdirectory_example SOURCE WORK GENERATOR CXX)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE}/docs/examples/subdirectory -B ${WORK} -G ${GENERATOR}
                        -DCMAKE_CXX_COMPILER=${CXX} -DAESIM_SOURCE=${SOURCE}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "configuring the project failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} -N WORKING_DIRECTORY ${WORK} OUTPUT_VARIABLE listing)
if(NOT listing MATCHES "Total Tests: 1\n" OR NOT listing MATCHES "my_sim[.]runs")
  message(FATAL_ERROR "aesim's tests leaked into the project's CTest:\n${listing}")
endif()
# The object's target name holds the source's path: Ninja lists it.
load_cache(${WORK} READ_WITH_PREFIX project_ CMAKE_MAKE_PROGRAM)
execute_process(COMMAND ${project_CMAKE_MAKE_PROGRAM} -t targets all WORKING_DIRECTORY ${WORK} OUTPUT_VARIABLE targets)
if(NOT targets MATCHES "(CMakeFiles/my_sim[.]dir/[^:\n]*embed_example[.]cpp[.]o):")
  message(FATAL_ERROR "no object of embed_example.cpp among the project's targets (GENERATOR Ninja only)")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK} --target ${CMAKE_MATCH_1}
                RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "compiling the example in the project failed:\n${out}\n${err}")
endif()
message(STATUS "subdirectory_example: configured, only the project's own test, the example compiles")
