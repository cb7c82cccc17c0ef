# One function for a lagfsi module (a static library with its own include root and unit tests):
#
#   lagfsi_add_module(<name> SOURCES <files>... [INCLUDE_DIR <dir>] [PUBLIC <targets>...] [PRIVATE <targets>...])
#
# makes lagfsi_<name> with the alias lagfsi::<name>, its public include root (default: <module folder>/include,
# where the module's headers sit under lagfsi/<name>/), the common compile settings (lagfsi_options), the
# dependencies the module declares (they point one way: app -> fsi -> models -> core -> meshing -> base; the fence
# tests in tests/fence check it), and the module's unit tests (<module folder>/tests) when tests are built.
function(lagfsi_add_module name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "INCLUDE_DIR" "SOURCES;PUBLIC;PRIVATE")
  if(NOT arg_SOURCES)
    message(FATAL_ERROR "lagfsi_add_module(${name}): no SOURCES")
  endif()
  if(NOT arg_INCLUDE_DIR)
    set(arg_INCLUDE_DIR ${CMAKE_CURRENT_SOURCE_DIR}/include)
  endif()
  add_library(lagfsi_${name} STATIC ${arg_SOURCES})
  add_library(lagfsi::${name} ALIAS lagfsi_${name})
  target_include_directories(lagfsi_${name} PUBLIC ${arg_INCLUDE_DIR})
  target_link_libraries(lagfsi_${name} PUBLIC ${arg_PUBLIC} PRIVATE lagfsi_options ${arg_PRIVATE})
  if(LAGFSI_BUILD_TESTS AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/tests/CMakeLists.txt)
    add_subdirectory(tests)  # unit tests of this module alone (label unit)
  endif()
endfunction()
