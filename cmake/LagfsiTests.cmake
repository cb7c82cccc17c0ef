# GoogleTest helpers: one executable per test file.
#
#   lagfsi_add_test(<source> LABEL <label> TIMEOUT <seconds> [LINK <targets>...] [WHITE_BOX] [RUNS_EXE] [ENV <v=x>...])
#   lagfsi_unit_test(<source> <module target> [WHITE_BOX] [RUNS_EXE] [LINK <more>...] [ENV <v=x>...])
#   (label unit, 120 s)
# ENV: the test's ENVIRONMENT_MODIFICATION entries ("VAR=set:value"; LAGFSI_PETSC_TEST_ENV: what a test that starts
# PETSc needs).
#
# A unit test (src/<module>/tests, meshing/tests, fsi/tests) links its module alone (and GoogleTest), so it proves
# the module builds and links on its own. WHITE_BOX adds the module's folder (its private headers) to the test's
# include path; RUNS_EXE builds the `lagfsi` executable first (tests that run it through tests/support). Every test
# sees tests/support and the macros LAGFSI_SOURCE_DIR, LAGFSI_BINARY_DIR, LAGFSI_EXE.
# Under the sanitizers (the Developer preset), MPI, hwloc and PETSc keep allocations of their start-up to the end
# of the process, some in plug-ins unloaded by then: LeakSanitizer is told to ignore those libraries (with full
# stacks, so that an allocation made through a plug-in is traced to them; without the table of suppressions used,
# which would add lines to the stderr a test reads). No effect on a Release build.
set(LAGFSI_PETSC_TEST_ENV
    "LSAN_OPTIONS=set:suppressions=${PROJECT_SOURCE_DIR}/scripts/lsan_suppressions.txt:fast_unwind_on_malloc=0:print_suppressions=0")

# The test file's executable `name` (linked with `links`, GoogleTest and its main); white_box: the module's folder
# on its include path.
function(lagfsi_test_executable name source white_box)
  add_executable(${name} ${source})
  target_link_libraries(${name} PRIVATE ${ARGN} nlohmann_json::nlohmann_json lagfsi_options GTest::gtest
                                        GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests/support)
  if(white_box)
    get_filename_component(module_dir ${CMAKE_CURRENT_SOURCE_DIR} DIRECTORY)
    target_include_directories(${name} PRIVATE ${module_dir})
  endif()
endfunction()

function(lagfsi_add_test source)
  cmake_parse_arguments(PARSE_ARGV 1 arg "WHITE_BOX;RUNS_EXE" "LABEL;TIMEOUT" "LINK;ENV")
  get_filename_component(name ${source} NAME_WE)
  lagfsi_test_executable(${name} ${source} "${arg_WHITE_BOX}" ${arg_LINK})
  # GCC 12 reports a false -Wrestrict inside libstdc++ for "literal" + std::to_string(...) at -O2/-O3
  # (GCC bug 105329); the test names are built that way.
  target_compile_options(${name} PRIVATE $<$<AND:$<CXX_COMPILER_ID:GNU>,$<VERSION_LESS:$<CXX_COMPILER_VERSION>,13>>:-Wno-restrict>)
  target_compile_definitions(${name} PRIVATE
    LAGFSI_SOURCE_DIR="${PROJECT_SOURCE_DIR}" LAGFSI_BINARY_DIR="${PROJECT_BINARY_DIR}"
    LAGFSI_EXE="$<TARGET_FILE:lagfsi>")
  if(arg_RUNS_EXE)
    add_dependencies(${name} lagfsi)
  endif()
  # One OpenMP thread per test: ctest runs tests in parallel on this 2-core machine, and spinning OpenMP
  # barriers of oversubscribed threads make runs 5-20x slower (speed is measured by tests/bench).
  set(properties LABELS ${arg_LABEL} TIMEOUT ${arg_TIMEOUT} ENVIRONMENT "OMP_NUM_THREADS=1")
  if(arg_ENV)
    list(APPEND properties ENVIRONMENT_MODIFICATION "${arg_ENV}")
  endif()
  gtest_discover_tests(${name} PROPERTIES ${properties} DISCOVERY_TIMEOUT 60)
endfunction()

function(lagfsi_unit_test source module)
  cmake_parse_arguments(PARSE_ARGV 2 arg "WHITE_BOX;RUNS_EXE" "" "LINK;ENV")
  set(flags)
  foreach(flag WHITE_BOX RUNS_EXE)
    if(arg_${flag})
      list(APPEND flags ${flag})
    endif()
  endforeach()
  lagfsi_add_test(${source} LABEL unit TIMEOUT 120 LINK ${module} ${arg_LINK} ${flags} ENV ${arg_ENV})
endfunction()

# A unit test run under MPI (label unit): the test file's executable under `mpiexec -np P` for each P of PROCESSES
# (oversubscribed, as root in CI), one CTest test per count, named <NAME>.OnPProcesses. The test starts MPI itself
# (mpi_run::start).
#   lagfsi_mpi_unit_test(<source> <module target> NAME <name> PROCESSES <P>... [WHITE_BOX])
function(lagfsi_mpi_unit_test source module)
  cmake_parse_arguments(PARSE_ARGV 2 arg "WHITE_BOX" "NAME" "PROCESSES")
  get_filename_component(name ${source} NAME_WE)
  lagfsi_test_executable(${name} ${source} "${arg_WHITE_BOX}" ${module})
  foreach(p ${arg_PROCESSES})
    add_test(NAME ${arg_NAME}.On${p}Processes
             COMMAND ${MPIEXEC_EXECUTABLE} --allow-run-as-root --oversubscribe ${MPIEXEC_NUMPROC_FLAG} ${p}
                     $<TARGET_FILE:${name}>)
    set_tests_properties(${arg_NAME}.On${p}Processes PROPERTIES LABELS unit TIMEOUT 120 ENVIRONMENT "OMP_NUM_THREADS=1"
                         ENVIRONMENT_MODIFICATION "${LAGFSI_PETSC_TEST_ENV}")
  endforeach()
endfunction()
