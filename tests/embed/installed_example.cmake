# Shared by the tests of the out-of-tree examples: aesim installed from BUILD into a fresh prefix
# under WORK, and the example in SOURCE/docs/examples/<name> configured with find_package(aesim)
# against that prefix alone (with any further configure arguments given), then built in
# WORK/example.

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

function(build_installed_example name)
  file(REMOVE_RECURSE ${WORK})
  run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix)
  run("configuring the example" ${CMAKE_COMMAND} -S ${SOURCE}/docs/examples/${name} -B ${WORK}/example -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF ${ARGN})
  run("building the example" ${CMAKE_COMMAND} --build ${WORK}/example)
endfunction()
