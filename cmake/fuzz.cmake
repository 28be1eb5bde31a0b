# libFuzzer harnesses (tests/fuzz/) for the scene, mesh (through assimp, and the decoding of the
# import process's answer), command-stream and UnitConfig readers,
# built with clang + ASan + UBSan as a project of their own in <build>/fuzz (the main build's
# compiler need not be clang), and one ctest per harness that runs it for a bounded number of
# inputs from its seed corpus. A crash, hang, leak, sanitizer report or an exception that is not
# the reader's documented error type fails the test. The crashing inputs found so far are kept
# in tests/fuzz/regressions/<harness>/ and run once each as their own tests.
include(ExternalProject)

set(SHADESIM_FUZZ_RUNS 100000 CACHE STRING "Inputs each fuzz ctest runs at most")
set(SHADESIM_FUZZ_SECONDS 10 CACHE STRING
    "Seconds each fuzz ctest runs at most (a smoke run in CI; scripts/fuzz runs longer by hand)")

find_program(SHADESIM_CLANGXX NAMES clang++ clang++-14 DOC "clang++ for the libFuzzer harnesses")
set(fuzz_probe_ok FALSE)
if(SHADESIM_CLANGXX)
  # libFuzzer is a separate Debian package (libclang-rt-14-dev): link a one-line fuzzer to know.
  set(probe_dir ${CMAKE_BINARY_DIR}/fuzz-probe)
  file(MAKE_DIRECTORY ${probe_dir})
  file(WRITE ${probe_dir}/probe.cpp
       "#include <cstdint>\n#include <cstddef>\nextern \"C\" int LLVMFuzzerTestOneInput("
       "const uint8_t*, size_t) { return 0; }\n")
  execute_process(COMMAND ${SHADESIM_CLANGXX} -fsanitize=fuzzer,address,undefined
                          ${probe_dir}/probe.cpp -o ${probe_dir}/probe
                  RESULT_VARIABLE probe_result OUTPUT_QUIET ERROR_VARIABLE probe_error)
  if(probe_result EQUAL 0)
    set(fuzz_probe_ok TRUE)
  endif()
endif()
if(NOT fuzz_probe_ok)
  message(FATAL_ERROR
          "SHADESIM_FUZZ is ON but clang++ with libFuzzer and ASan/UBSan was not found "
          "(clang++: '${SHADESIM_CLANGXX}'; ${probe_error}). Install the Debian packages clang and "
          "libclang-rt-14-dev (scripts/setup does), or configure with -DSHADESIM_FUZZ=OFF to "
          "build and test without the fuzzers.")
endif()
message(STATUS "shadesim: libFuzzer harnesses with ${SHADESIM_CLANGXX} in ${CMAKE_BINARY_DIR}/fuzz")

# The mesh harnesses' seeds come from assimp-testmodels' files, its malformed ones too.
set(mesh_models /usr/share/assimp/models)
if(NOT IS_DIRECTORY ${mesh_models})
  message(FATAL_ERROR "SHADESIM_FUZZ: ${mesh_models} not found; the mesh fuzzers' seed corpora "
                      "come from the Debian package assimp-testmodels (scripts/setup installs it)")
endif()

set(fuzz_dir ${CMAKE_BINARY_DIR}/fuzz)
set(fuzz_targets scene mesh mesh_answer command_stream unit_config)
set(fuzz_executables)
foreach(target ${fuzz_targets})
  list(APPEND fuzz_executables ${fuzz_dir}/fuzz_${target})
endforeach()
ExternalProject_Add(shadesim_fuzzers
  SOURCE_DIR ${CMAKE_SOURCE_DIR}/tests/fuzz
  BINARY_DIR ${fuzz_dir}
  CMAKE_ARGS -DCMAKE_CXX_COMPILER=${SHADESIM_CLANGXX} -DCMAKE_BUILD_TYPE=RelWithDebInfo
             -DSHADESIM_SOURCE_DIR=${CMAKE_SOURCE_DIR} -DMESH_MODELS=${mesh_models}
  CMAKE_GENERATOR ${CMAKE_GENERATOR}
  BUILD_ALWAYS ON  # its own build tool decides what is out of date
  BUILD_BYPRODUCTS ${fuzz_executables}
  INSTALL_COMMAND "")

# fuzz_mesh's seeds: those files with the extension line the harness expects (fuzz_mesh_answer's
# are written by its build, tests/fuzz/CMakeLists.txt).
execute_process(COMMAND bash ${CMAKE_SOURCE_DIR}/tests/fuzz/mesh_seeds.sh ${mesh_models}
                        ${fuzz_dir}/seeds/mesh
                RESULT_VARIABLE seeds_result OUTPUT_QUIET)
if(NOT seeds_result EQUAL 0)
  message(FATAL_ERROR "SHADESIM_FUZZ: tests/fuzz/mesh_seeds.sh failed")
endif()

foreach(target ${fuzz_targets})
  # scripts/fuzz holds the flags and the seed folders (the same as a long run's): new inputs go
  # to <build>/fuzz/corpus/<target>, the seeds are only read, -seed=1 fixes the run.
  file(MAKE_DIRECTORY ${fuzz_dir}/corpus/${target})
  add_test(NAME fuzz_${target}
    COMMAND ${CMAKE_SOURCE_DIR}/scripts/fuzz --build ${CMAKE_BINARY_DIR} --runs ${SHADESIM_FUZZ_RUNS}
            --seconds ${SHADESIM_FUZZ_SECONDS} ${target})
  set_tests_properties(fuzz_${target} PROPERTIES TIMEOUT 300)
  file(GLOB regressions CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/tests/fuzz/regressions/${target}/*)
  if(regressions)
    add_test(NAME fuzz_${target}_regressions COMMAND ${fuzz_dir}/fuzz_${target} ${regressions})
    set_tests_properties(fuzz_${target}_regressions PROPERTIES TIMEOUT 300)
  endif()
endforeach()
