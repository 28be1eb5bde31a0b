# span_setup's Booth product, exhaustively (tests/rtl/tb_span_setup_booth.sv) under Icarus:
#   cmake -DIVERILOG=iverilog -DVVP=vvp -DSRC=source -DWORK=folder [-DBREAK=ON]
#         -P tests/rtl/booth_check.cmake
# BREAK=ON runs it on a copy of rtl/span_setup.sv whose +-2t Booth digits are +-t: the check
# must then fail (the test can fail), else this script does.
foreach(var IVERILOG VVP SRC WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "booth check: -D${var}=... is required")
  endif()
endforeach()
file(MAKE_DIRECTORY ${WORK})
# The RTL read: $SHADESIM_RTL_DIR when set (a mutant's copy, scripts/mutate-rtl), else SRC/rtl.
set(rtl ${SRC}/rtl)
if(DEFINED ENV{SHADESIM_RTL_DIR} AND NOT "$ENV{SHADESIM_RTL_DIR}" STREQUAL "")
  set(rtl $ENV{SHADESIM_RTL_DIR})
endif()
set(setup ${rtl}/span_setup.sv)
if(BREAK)
  file(READ ${setup} text)
  string(REPLACE "mag = t << 1;" "mag = t;" broken "${text}")
  if(broken STREQUAL text)
    message(FATAL_ERROR "booth check: ${setup} has no `mag = t << 1;` to break")
  endif()
  set(setup ${WORK}/span_setup_broken.sv)
  file(WRITE ${setup} "${broken}")
endif()
# -DSYNTHESIS: the Booth form is span_setup's synthesis view (simulators otherwise multiply).
execute_process(COMMAND ${IVERILOG} -g2012 -DSYNTHESIS -s tb_span_setup_booth -o ${WORK}/booth.vvp
                        ${rtl}/shade_pkg.sv ${rtl}/fixed_round.sv ${rtl}/fixed_sat.sv
                        ${setup} ${SRC}/tests/rtl/tb_span_setup_booth.sv
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "booth check: iverilog failed (${rc}):\n${out}${err}")
endif()
execute_process(COMMAND ${VVP} -n ${WORK}/booth.vvp
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(BREAK)
  if(rc EQUAL 0 OR NOT out MATCHES "booth: FAIL")
    message(FATAL_ERROR "booth check: the broken Booth digits were not caught (${rc}):\n${out}${err}")
  endif()
  message(STATUS "the broken Booth digits were caught:\n${out}")
  return()
endif()
if(NOT rc EQUAL 0 OR NOT out MATCHES "booth: PASS")
  message(FATAL_ERROR "booth check: failed (${rc}):\n${out}${err}")
endif()
message(STATUS "${out}")
