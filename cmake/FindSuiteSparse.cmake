# FindSuiteSparse
# ---------------
# Debian 12 ships SuiteSparse 5.x without CMake configuration files; this module finds the headers and
# libraries of the requested components and defines imported targets.
#
#   find_package(SuiteSparse REQUIRED COMPONENTS CHOLMOD UMFPACK KLU)
#
# Result variables: SuiteSparse_FOUND, SuiteSparse_VERSION, SuiteSparse_INCLUDE_DIR,
#                   SuiteSparse_<C>_LIBRARY, SuiteSparse_<C>_FOUND.
# Imported targets: SuiteSparse::config, SuiteSparse::AMD, SuiteSparse::COLAMD, SuiteSparse::BTF,
#                   SuiteSparse::CHOLMOD, SuiteSparse::UMFPACK, SuiteSparse::KLU.
include(FindPackageHandleStandardArgs)

find_path(SuiteSparse_INCLUDE_DIR NAMES SuiteSparse_config.h
  PATH_SUFFIXES suitesparse include/suitesparse)

if(SuiteSparse_INCLUDE_DIR AND EXISTS "${SuiteSparse_INCLUDE_DIR}/SuiteSparse_config.h")
  file(STRINGS "${SuiteSparse_INCLUDE_DIR}/SuiteSparse_config.h" _ss_lines
       REGEX "#define SUITESPARSE_(MAIN|SUB|SUBSUB)_VERSION[ \t]+[0-9]+")
  foreach(_part MAIN SUB SUBSUB)
    string(REGEX REPLACE ".*SUITESPARSE_${_part}_VERSION[ \t]+([0-9]+).*" "\\1" _v_${_part} "${_ss_lines}")
  endforeach()
  set(SuiteSparse_VERSION "${_v_MAIN}.${_v_SUB}.${_v_SUBSUB}")
endif()

# Internal helper: one library + imported target.
function(_lagfsi_ss_lib target libname)
  string(TOUPPER ${target} _up)
  find_library(SuiteSparse_${_up}_LIBRARY NAMES ${libname})
  if(SuiteSparse_${_up}_LIBRARY)
    set(SuiteSparse_${target}_FOUND TRUE PARENT_SCOPE)
    if(NOT TARGET SuiteSparse::${target})
      add_library(SuiteSparse::${target} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${target} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_up}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
    endif()
  endif()
endfunction()

_lagfsi_ss_lib(config suitesparseconfig)
_lagfsi_ss_lib(AMD amd)
_lagfsi_ss_lib(COLAMD colamd)
_lagfsi_ss_lib(CAMD camd)
_lagfsi_ss_lib(CCOLAMD ccolamd)
_lagfsi_ss_lib(BTF btf)
_lagfsi_ss_lib(CHOLMOD cholmod)
_lagfsi_ss_lib(UMFPACK umfpack)
_lagfsi_ss_lib(KLU klu)

# Link dependencies between the components.
foreach(_t AMD COLAMD CAMD CCOLAMD BTF)
  if(TARGET SuiteSparse::${_t})
    set_property(TARGET SuiteSparse::${_t} APPEND PROPERTY INTERFACE_LINK_LIBRARIES SuiteSparse::config)
  endif()
endforeach()
if(TARGET SuiteSparse::CHOLMOD)
  set_property(TARGET SuiteSparse::CHOLMOD APPEND PROPERTY INTERFACE_LINK_LIBRARIES
    SuiteSparse::AMD SuiteSparse::COLAMD SuiteSparse::CAMD SuiteSparse::CCOLAMD SuiteSparse::config)
endif()
if(TARGET SuiteSparse::UMFPACK)
  set_property(TARGET SuiteSparse::UMFPACK APPEND PROPERTY INTERFACE_LINK_LIBRARIES
    SuiteSparse::CHOLMOD SuiteSparse::AMD SuiteSparse::config)
endif()
if(TARGET SuiteSparse::KLU)
  set_property(TARGET SuiteSparse::KLU APPEND PROPERTY INTERFACE_LINK_LIBRARIES
    SuiteSparse::BTF SuiteSparse::AMD SuiteSparse::COLAMD SuiteSparse::config)
endif()

set(_req_vars SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY)
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS ${_req_vars}
  VERSION_VAR SuiteSparse_VERSION
  HANDLE_COMPONENTS)
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
