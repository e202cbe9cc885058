# The installed headers as a project meets them: aesim installed into a fresh prefix, then every
# header under include/aesim compiled alone in a translation unit of its own, in a project that
# finds aesim with find_package against that prefix only. A public header that includes one left
# out of the install (AESIM_PUBLIC_HEADERS) or that needs another included before it fails here.
# An installed header that is not in the umbrella's closure is named too: the surface stays the
# one docs/embedding.md lists. The headers are compiled as the project's own (NO_SYSTEM_FROM_IMPORTED):
# an imported target's include folder is a system one, where the compilers keep quiet, and a user
# who includes aesim's headers through -I must not meet warnings from them. Only the front end
# runs (-fsyntax-only): a header alone makes no code worth generating.
#   cmake -DBUILD=<aesim build> -DWORK=<scratch> -DGENERATOR=<gen> -P this
cmake_policy(VERSION 3.22)
include(${CMAKE_CURRENT_LIST_DIR}/required_definitions.cmake)
require_definitions(public_headers BUILD WORK GENERATOR)
set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix} RESULT_VARIABLE status OUTPUT_QUIET
                ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${err}")
endif()
file(GLOB_RECURSE headers RELATIVE ${prefix}/include ${prefix}/include/*)
list(LENGTH headers n)
if(n LESS 10)
  message(FATAL_ERROR "only ${n} headers installed under ${prefix}/include")
endif()

set(project ${WORK}/project)
set(sources "")
set(i 0)
foreach(header ${headers})
  math(EXPR i "${i} + 1")
  file(WRITE ${project}/header_${i}.cpp "#include <${header}>\n#include <${header}>\n")
  list(APPEND sources header_${i}.cpp)
endforeach()
# Which installed headers the umbrella does not reach: read the includes, header by header.
set(reached aesim/aesim.hpp)
set(queue aesim/aesim.hpp)
while(queue)
  list(POP_FRONT queue header)
  file(STRINGS ${prefix}/include/${header} lines REGEX "^#include [\"<]aesim/")
  foreach(line ${lines})
    string(REGEX REPLACE "^#include [\"<](aesim/[^\">]+)[\">].*" "\\1" included ${line})
    if(NOT EXISTS ${prefix}/include/${included})
      message(FATAL_ERROR "${header} includes ${included}, which is not installed (AESIM_PUBLIC_HEADERS)")
    endif()
    if(NOT included IN_LIST reached)
      list(APPEND reached ${included})
      list(APPEND queue ${included})
    endif()
  endforeach()
endwhile()
foreach(header ${headers})
  if(NOT header IN_LIST reached)
    message(FATAL_ERROR "${header} is installed but <aesim/aesim.hpp> does not include it")
  endif()
endforeach()
list(JOIN sources ";" source_list)
file(WRITE ${project}/umbrella.cpp "#include <aesim/aesim.hpp>\n")
file(WRITE ${project}/CMakeLists.txt "cmake_minimum_required(VERSION 3.22)
project(public_headers LANGUAGES CXX)
find_package(aesim REQUIRED)
set(HEADER_SOURCES \"${source_list}\" CACHE STRING \"the translation units, each one header\")
add_library(public_headers OBJECT \${HEADER_SOURCES})
target_link_libraries(public_headers PRIVATE aesim::aesim)
set_target_properties(public_headers PROPERTIES NO_SYSTEM_FROM_IMPORTED ON)
target_compile_options(public_headers PRIVATE -fsyntax-only -Wall -Wextra -Wpedantic -Wshadow -Woverloaded-virtual
                                              -Wconversion -Wsign-conversion -Wold-style-cast -Wnon-virtual-dtor
                                              -Wcast-align -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough
                                              -Werror)
")
# The warnings are those a strict project turns on (conversions and signs, C casts, a virtual
# class without a virtual destructor), since a header's warning is the including project's error.
# A user's project may build with GCC or clang, whose warnings differ (clang's: a virtual overridden
# without `override`, one hidden by an overload): warning-free under both, as errors. Each header
# alone under GCC; under clang the umbrella, whose closure is every installed header (checked above):
# whether a header stands alone does not depend on the compiler, its warnings do. GCC compiles them
# as C++17, the standard aesim is built in, clang as C++20 (its deprecations warn too).
find_program(CLANGXX clang++)
set(i 0)
foreach(cxx default ${CLANGXX})
  math(EXPR i "${i} + 1")
  set(compiler_options "")
  if(NOT cxx STREQUAL "default")
    set(compiler_options -DCMAKE_CXX_COMPILER=${cxx} -DHEADER_SOURCES=umbrella.cpp -DCMAKE_CXX_STANDARD=20)
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${project} -B ${project}/build${i} -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Debug
                          -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF ${compiler_options}
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "configuring against the prefix failed (${cxx}):\n${out}\n${err}")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${project}/build${i} RESULT_VARIABLE status OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "an installed header does not compile alone, warning-free (${cxx} compiler):\n${out}\n${err}")
  endif()
endforeach()
message(STATUS "${n} installed headers, each compiles alone against the prefix warning-free under GCC, all of them under clang as C++20")
