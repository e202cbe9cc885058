# SystemC as one imported target, SystemC::systemc, for aesim's own build and for a project that
# finds the installed aesim package (this file is installed beside aesimConfig.cmake). SystemC's
# own CMake package when there is one (a SystemC built from source installs it); else Debian's
# pkg-config file, wrapped so that the name a project sees is SystemC::systemc, never PkgConfig's.
if(NOT TARGET SystemC::systemc)
  find_package(SystemCLanguage CONFIG QUIET)
  if(SystemCLanguage_FOUND AND TARGET SystemC::systemc)
    return()
  endif()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(AESIM_SYSTEMC REQUIRED IMPORTED_TARGET systemc)
  add_library(SystemC::systemc INTERFACE IMPORTED)
  set_target_properties(SystemC::systemc PROPERTIES INTERFACE_LINK_LIBRARIES PkgConfig::AESIM_SYSTEMC)
endif()
