# A synthesis view of the RTL (the `ifdef SYNTHESIS` form Yosys reads where simulators take
# Verilog's `*`), checked exhaustively under Icarus against `*` by a testbench of its own:
#   cmake -DVIEW=booth|square -DIVERILOG=iverilog -DVVP=vvp -DSRC=source -DWORK=folder
#         [-DBREAK=ON] -P tests/rtl/synthesis_view_check.cmake
#   booth   span_setup's radix-4 Booth product (tests/rtl/tb_span_setup_booth.sv)
#   square  wpow_unit's squarer, summed as a square (tests/rtl/tb_wpow_square.sv)
# BREAK=ON runs it on a copy of the module with one deliberate slip (booth: the +-2t digits made
# +-t; square: every row's b_i & b_j one place too low): the check must then fail (the test can
# fail), else this script does. Each testbench prints "<VIEW>: PASS" or "<VIEW>: FAIL".
foreach(var VIEW IVERILOG VVP SRC WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "synthesis view check: -D${var}=... is required")
  endif()
endforeach()
if(VIEW STREQUAL "booth")
  set(module span_setup)
  set(tb tb_span_setup_booth)
  set(good "mag = t << 1;")
  set(bad "mag = t;")
elseif(VIEW STREQUAL "square")
  set(module wpow_unit)
  set(tb tb_wpow_square)
  set(good "(b >> (i + 1))")
  set(bad "(b >> i)")
else()
  message(FATAL_ERROR "synthesis view check: -DVIEW=${VIEW}: expected booth or square")
endif()
file(MAKE_DIRECTORY ${WORK})
# The RTL read: $SHADESIM_RTL_DIR when set (a mutant's copy, scripts/mutate-rtl), else SRC/rtl.
set(rtl ${SRC}/rtl)
if(DEFINED ENV{SHADESIM_RTL_DIR} AND NOT "$ENV{SHADESIM_RTL_DIR}" STREQUAL "")
  set(rtl $ENV{SHADESIM_RTL_DIR})
endif()
set(source ${rtl}/${module}.sv)
if(BREAK)
  file(READ ${source} text)
  string(REPLACE "${good}" "${bad}" broken "${text}")
  if(broken STREQUAL text)
    message(FATAL_ERROR "${VIEW} check: ${source} has no `${good}` to break")
  endif()
  set(source ${WORK}/${module}_broken.sv)
  file(WRITE ${source} "${broken}")
endif()
# -DSYNTHESIS: the view under test (simulators otherwise multiply).
execute_process(COMMAND ${IVERILOG} -g2012 -DSYNTHESIS -I${SRC}/tests/rtl -s ${tb}
                        -o ${WORK}/${VIEW}.vvp
                        ${rtl}/shade_pkg.sv ${rtl}/fixed_round.sv ${rtl}/fixed_sat.sv
                        ${source} ${SRC}/tests/rtl/${tb}.sv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${VIEW} check: iverilog failed (${rc}):\n${out}${err}")
endif()
execute_process(COMMAND ${VVP} -n ${WORK}/${VIEW}.vvp
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(BREAK)
  if(rc EQUAL 0 OR NOT out MATCHES "${VIEW}: FAIL")
    message(FATAL_ERROR "${VIEW} check: the broken ${module} was not caught (${rc}):\n${out}${err}")
  endif()
  message(STATUS "the broken ${module} was caught:\n${out}")
  return()
endif()
if(NOT rc EQUAL 0 OR NOT out MATCHES "${VIEW}: PASS")
  message(FATAL_ERROR "${VIEW} check: failed (${rc}):\n${out}${err}")
endif()
message(STATUS "${out}")
