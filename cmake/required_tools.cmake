# No silent skips: every test the project has needs a tool, and a missing tool fails
# the configure with the Debian package to install, unless the user opts out explicitly. What an
# opt-out leaves out is registered as a ctest that reports itself Skipped, so the test summary
# names it ("The following tests did not run: ... left_out_...").
#
#   -DSHADESIM_RTL=OFF                  no RTL at all (Verilator, Icarus and Yosys not needed)
#   -DSHADESIM_ALLOW_MISSING_TOOLS=ON   the tests of whichever tools (or assimp-testmodels) are
#                                       missing left out
#   -DSHADESIM_FUZZ=OFF                 no libFuzzer harnesses (cmake/fuzz.cmake)
option(SHADESIM_ALLOW_MISSING_TOOLS
       "With SHADESIM_RTL=ON: configure although Verilator, Icarus or Yosys is missing; their tests are left out and listed as skipped" OFF)

# A ctest that reports `what` as left out (ctest counts it Skipped, never Passed).
function(shadesim_left_out name what)
  add_test(NAME left_out_${name} COMMAND sh -c "echo 'left out: ${what}'; exit 77")
  set_tests_properties(left_out_${name} PROPERTIES SKIP_RETURN_CODE 77 LABELS left_out)  # + its tier: cmake/test_tiers.cmake
endfunction()

# Real and malformed meshes nobody here wrote (Debian's assimp-testmodels): the mesh, scene and
# render tests need them with or without RTL. Allowed missing, those tests skip themselves
# (tests/support/test_data.h); otherwise they would fail, so say so now.
set(SHADESIM_ASSIMP_MODELS /usr/share/assimp/models)
if(NOT EXISTS ${SHADESIM_ASSIMP_MODELS}/BLEND/Suzanne_248.blend)
  if(NOT SHADESIM_ALLOW_MISSING_TOOLS)
    message(FATAL_ERROR "shadesim: ${SHADESIM_ASSIMP_MODELS} (Debian package assimp-testmodels) is "
                        "missing; the mesh tests need it. Install it (scripts/setup does), or "
                        "configure with -DSHADESIM_ALLOW_MISSING_TOOLS=ON to skip those tests.")
  endif()
  shadesim_left_out(assimp_testmodels "assimp-testmodels: the real-mesh and malformed-mesh tests skip")
endif()

if(NOT SHADESIM_RTL)
  shadesim_left_out(rtl "SHADESIM_RTL=OFF: Verilator co-simulation, Icarus, Yosys and RTL unit tests were not configured")
  return()
endif()

find_package(verilator 5 QUIET HINTS $ENV{VERILATOR_ROOT})
find_program(IVERILOG iverilog)
find_program(VVP vvp)
find_program(YOSYS yosys)
set(missing_tools)
if(NOT verilator_FOUND)
  list(APPEND missing_tools "Verilator 5 (Debian package verilator): RTL co-simulation, lint, RTL unit tests and the Icarus checks (compared with it)")
endif()
if(NOT IVERILOG OR NOT VVP)
  list(APPEND missing_tools "Icarus Verilog iverilog/vvp (Debian package iverilog): Icarus checks")
endif()
if(NOT YOSYS)
  list(APPEND missing_tools "Yosys (Debian package yosys): latch checks and area tests")
endif()
if(missing_tools)
  list(JOIN missing_tools "\n  " listed)
  if(NOT SHADESIM_ALLOW_MISSING_TOOLS)
    message(FATAL_ERROR "shadesim: SHADESIM_RTL is ON but these tools are missing:\n  ${listed}\n"
                        "Install them (scripts/setup installs every package), or configure with "
                        "-DSHADESIM_RTL=OFF (no RTL) or -DSHADESIM_ALLOW_MISSING_TOOLS=ON (leave out "
                        "what needs them; ctest lists it as skipped).")
  endif()
  message(WARNING "shadesim: SHADESIM_ALLOW_MISSING_TOOLS=ON, leaving out:\n  ${listed}")
  set(i 0)
  foreach(tool ${missing_tools})
    math(EXPR i "${i} + 1")
    shadesim_left_out(tool_${i} "${tool}")
  endforeach()
endif()
