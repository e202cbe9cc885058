# AESIM_SYSTEMC_CPLUSPLUS: the C++ standard SystemC's library was built for, as SystemC's headers
# name it (SC_CPLUSPLUS). Every translation unit that includes them refers to a symbol named after
# that standard (sc_api_version_2_3_4_cxx201703L), which the library defines for its own only: a
# project compiled as C++20 against Debian's library (built as C++17) fails to link, on an
# undefined sc_api_version_..._cxx202002L, unless it defines SC_CPLUSPLUS as the library's. aesim
# defines it for its own sources and on aesim::aesim and in aesim.pc, so that a project links
# whatever standard from C++17 on it compiles as. Found once, by the first of the standards below
# that links against SystemC::systemc, and cached (-DAESIM_SYSTEMC_CPLUSPLUS=... sets it).
if(NOT DEFINED AESIM_SYSTEMC_CPLUSPLUS)
  set(probe_dir ${CMAKE_BINARY_DIR}/CMakeFiles/aesim_systemc_cplusplus)
  file(WRITE ${probe_dir}/probe.cpp "#include <systemc>\nint sc_main(int, char*[]) { return 0; }\n")
  foreach(candidate 201703L 202002L 201402L 202302L)
    try_compile(links ${probe_dir}/${candidate} ${probe_dir}/probe.cpp
                COMPILE_DEFINITIONS -DSC_CPLUSPLUS=${candidate}
                LINK_LIBRARIES SystemC::systemc
                CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON)
    if(links)
      set(AESIM_SYSTEMC_CPLUSPLUS ${candidate} CACHE STRING "The C++ standard SystemC's library was built for (SC_CPLUSPLUS)")
      break()
    endif()
  endforeach()
  if(NOT DEFINED AESIM_SYSTEMC_CPLUSPLUS)
    message(FATAL_ERROR "no C++ standard links against SystemC (tried SC_CPLUSPLUS = 201703L, 202002L, 201402L, "
                        "202302L): set AESIM_SYSTEMC_CPLUSPLUS to the one its library was built for")
  endif()
  message(STATUS "SystemC's library was built for C++ ${AESIM_SYSTEMC_CPLUSPLUS} (SC_CPLUSPLUS)")
endif()
