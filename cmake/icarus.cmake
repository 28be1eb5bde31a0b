# Icarus Verilog as an independent simulator of the same RTL (rtl/*.sv): the testbench
# sim/icarus/tb_shade_unit.sv replays a command stream's words under the Verilator harness's
# seeded gaps and back-pressure and writes its pixels with their exit cycles, which must equal
# the bit-accurate model's pixels and the cycle model's cycles; its cycle count must equal the
# Verilator C++ backend's on the same stream and stimulus. scripts/bench-cosim times it against
# the Verilator backends. Included after cmake/rtl.cmake (it uses RTL_SOURCES, RTL_CACHE,
# RTL_BUILD_NAMES and SHADESIM_CLI).
#
# The testbench of a named build is compiled with the build's parameters, which shadesim prints
# from the one mapping (shadesim rtl-params --tool iverilog); iverilog -P sets parameters of the
# root module only, so each must be one the testbench declares and passes on (an unknown -P is
# only a warning, and the RTL would silently get its default): the check fails otherwise, and
# icarus_tb_params (sim/icarus/tb_params_check.cmake) fails as soon as shade_unit has a
# parameter the testbench does not mirror.
#
# The same file, run as a script (cmake -DICARUS_CHECK=ON ... -P cmake/icarus.cmake), is one
# check: random stream (and its scenario's stimulus) -> hex words, gap and per-cycle schedules,
# model pixels with the cycle model's exit cycles -> testbench -> vvp -> compare (and, given
# CACHE, the cycle count against the Verilator C++ backend's under the same stimulus).
# STIM="--gap-pct G --max-gap M --stall-pct P" replaces the scenario's stimulus (seed SEED). With -DCOMPILE_ONLY=ON it only
# compiles the testbench (scripts/bench-cosim).

if(CMAKE_SCRIPT_MODE_FILE)
  cmake_policy(VERSION 3.18)  # script mode starts with no policies set (list(FILTER), IN_LIST)
  if(NOT ICARUS_CHECK)
    message(FATAL_ERROR "icarus.cmake: run as a script only with -DICARUS_CHECK=ON")
  endif()
  foreach(var SHADESIM IVERILOG TB_SRC RTL TB CONFIG WORK)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "icarus check: -D${var}=... is required")
    endif()
  endforeach()
  file(MAKE_DIRECTORY ${WORK})
  function(_icarus_step what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "icarus check: ${what} failed (${rc}):\n  ${ARGN}\n${out}${err}")
    endif()
    set(step_out "${out}" PARENT_SCOPE)
  endfunction()
  # The testbench, compiled with the build's parameters.
  _icarus_step("rtl-params" ${SHADESIM} rtl-params --config ${CONFIG} --tool iverilog)
  string(REPLACE "\n" ";" params "${step_out}")
  list(FILTER params EXCLUDE REGEX "^$")
  file(READ ${TB_SRC} tb_text)
  foreach(p ${params})
    string(REGEX REPLACE "^-Ptb_shade_unit\\.([A-Za-z0-9_]+)=.*$" "\\1" pname "${p}")
    if(NOT tb_text MATCHES "parameter (int|logic \\[[^\n]*\\]) ${pname} ")
      message(FATAL_ERROR "icarus check: ${CONFIG} sets shade_unit parameter ${pname}, which "
                          "sim/icarus/tb_shade_unit.sv does not declare and pass on; add it there")
    endif()
  endforeach()
  string(REPLACE "," ";" rtl_sources "${RTL}")
  _icarus_step("iverilog" ${IVERILOG} -g2012 -s tb_shade_unit -DSHADESIM_FAULT_DUT=tb_shade_unit.dut
               ${params} -o ${TB} ${rtl_sources} ${TB_SRC})
  if(COMPILE_ONLY)
    return()
  endif()
  foreach(var TOOL VVP BUILDS SCENARIO SEED)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "icarus check: -D${var}=... is required")
    endif()
  endforeach()
  set(stem ${WORK}/${SCENARIO}_${SEED})
  _icarus_step("random stream" ${TOOL} random --builds ${BUILDS} --config ${CONFIG} --scenario ${SCENARIO} --seed ${SEED} --save ${stem}.cmds)
  # The scenario's stimulus (the harness's for `cosim --scenario`), unless STIM replaces it.
  if(NOT step_out MATCHES "stimulus: ([^\n]*)")
    message(FATAL_ERROR "icarus check: icarus_stream_tool random printed no stimulus:\n${step_out}")
  endif()
  if(STIM)
    separate_arguments(stim UNIX_COMMAND "--seed ${SEED} ${STIM}")
  else()
    separate_arguments(stim UNIX_COMMAND "${CMAKE_MATCH_1}")
  endif()
  _icarus_step("export" ${TOOL} export ${stem}.cmds --hex ${stem}.hex --pixels ${stem}.expected.txt
               --gaps ${stem}.gaps.hex --cycles ${stem}.cycles.hex ${stim})
  # FAULT=SITE@Y (a build with fault hooks): the plusargs its fault_select reads.
  set(fault_plusargs)
  if(FAULT)
    _icarus_step("fault plusargs" ${TOOL} fault-plusargs ${FAULT})
    separate_arguments(fault_plusargs UNIX_COMMAND "${step_out}")
  endif()
  string(TIMESTAMP t0 "%s")
  _icarus_step("vvp" ${VVP} -n ${TB} +words=${stem}.hex +gaps=${stem}.gaps.hex +cycles=${stem}.cycles.hex
               +pixels=${stem}.icarus.txt ${fault_plusargs})
  string(TIMESTAMP t1 "%s")
  math(EXPR vvp_seconds "${t1} - ${t0}")
  string(REPLACE ";" " " stim_text "${stim}")
  message(STATUS "${step_out}(vvp ${vvp_seconds} s; stimulus ${stim_text})")
  if(NOT step_out MATCHES "cycles=([0-9]+)")
    message(FATAL_ERROR "icarus check: the testbench printed no cycle count:\n${step_out}")
  endif()
  set(icarus_cycles ${CMAKE_MATCH_1})
  execute_process(COMMAND ${TOOL} compare ${stem}.expected.txt ${stem}.icarus.txt
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(EXPECT_MISMATCH_Y)
    # A deliberately broken RTL build: the comparison must fail, first on that scanline.
    if(rc EQUAL 0)
      message(FATAL_ERROR "icarus check: expected a mismatch at y=${EXPECT_MISMATCH_Y}, but the pixels and exit cycles are identical")
    endif()
    if(NOT err MATCHES "expected \"[0-9]+ ${EXPECT_MISMATCH_Y} ")
      message(FATAL_ERROR "icarus check: expected the first mismatch at y=${EXPECT_MISMATCH_Y}, got:\n${err}")
    endif()
    message(STATUS "the deliberate fault was caught where expected: ${err}")
    return()
  endif()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "icarus check: Icarus pixels or exit cycles differ from the bit-accurate model's and the cycle model's (stream ${stem}.cmds, ${stim_text}):\n${err}")
  endif()
  message(STATUS "${out}")
  if(CACHE)
    _icarus_step("shadesim cosim" ${SHADESIM} cosim --backend cpp --cache ${CACHE} --config ${CONFIG}
                 --stream ${stem}.cmds ${stim})
    if(NOT step_out MATCHES "cycles=([0-9]+)")
      message(FATAL_ERROR "icarus check: shadesim cosim printed no cycle count:\n${step_out}")
    endif()
    if(NOT CMAKE_MATCH_1 EQUAL icarus_cycles)
      message(FATAL_ERROR "icarus check: Icarus took ${icarus_cycles} cycles, Verilator ${CMAKE_MATCH_1} (stream ${stem}.cmds, ${stim_text})")
    endif()
    message(STATUS "cycles identical: ${icarus_cycles} (Icarus = Verilator)")
  endif()
  return()
endif()

find_program(IVERILOG iverilog)
find_program(VVP vvp)
if(NOT IVERILOG OR NOT VVP)
  message(WARNING "Icarus Verilog (iverilog, vvp) not found: Icarus checks and benchmark are skipped")
  return()
endif()
if(NOT SHADESIM_HAVE_RTL)
  message(WARNING "cmake/rtl.cmake found no Verilator: Icarus checks are skipped")
  return()
endif()

add_executable(icarus_stream_tool ${CMAKE_SOURCE_DIR}/sim/icarus/stream_tool.cpp)
shadesim_compile_lighter(icarus_stream_tool)
target_link_libraries(icarus_stream_tool PRIVATE shadesim_harness CLI11::CLI11)

set(ICARUS_DIR ${CMAKE_BINARY_DIR}/icarus)
set(ICARUS_TB ${CMAKE_SOURCE_DIR}/sim/icarus/tb_shade_unit.sv)
string(REPLACE ";" "," _rtl_list "${RTL_SIM_SOURCES}")
# Every named build (sim/harness/builds.json, so renamed or added builds follow) on one random
# `edge` stream (the value-space corners, three frames, commands after END_FRAME) under that
# scenario's gaps and back-pressure: Icarus pixels and exit cycles = the models', bit for bit and
# cycle for cycle, and its cycle count = the Verilator C++ backend's (the build the cosim tests
# use, from the same cache). Builds with fault hooks run fault-free here; two of the faults run
# below as expected failures, the others are left to the Verilator harness (cmake/rtl.cmake).
set(_icarus_check ${CMAKE_COMMAND} -DICARUS_CHECK=ON -DSHADESIM=${SHADESIM_CLI} -DIVERILOG=${IVERILOG}
    -DTB_SRC=${ICARUS_TB} -DRTL=${_rtl_list} -DTOOL=$<TARGET_FILE:icarus_stream_tool> -DVVP=${VVP}
    -DBUILDS=${CMAKE_SOURCE_DIR}/sim/harness/builds.json)
# An iterative specular unit takes a pixel every ~20 cycles, which makes an `edge` stream
# (12,000-34,000 pixels) cost minutes of Icarus: those builds run `short` (about 1,800 pixels)
# under edge's stimulus instead.
foreach(name ${RTL_BUILD_NAMES})
  set(_scenario -DSCENARIO=edge)
  foreach(unit schlick wpow)
    string(JSON timing ERROR_VARIABLE no_timing GET "${_builds_json}" ${name} unit specular ${unit} timing)
    if(NOT no_timing AND timing STREQUAL "iterative")
      set(_scenario -DSCENARIO=short "-DSTIM=--gap-pct 20 --max-gap 4 --stall-pct 30")
    endif()
  endforeach()
  add_test(NAME icarus_model_${name}
    COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/check/${name}/tb.vvp -DCONFIG=${name}
            -DWORK=${ICARUS_DIR}/check/${name} ${_scenario} -DSEED=11
            -DCACHE=${RTL_CACHE} -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
endforeach()
# The deliberate faults under gaps and back-pressure: one LSB on row 17 (a pixel mismatch) and
# one extra engine stall on row 23 (an exit-cycle mismatch), each first on its row. Back-pressure
# often hides the one-cycle stall (the output is stalled anyway: mixed seeds 1, 2, 3 and 5 pass on
# Verilator too); seed 4 is one where it shows.
add_test(NAME icarus_catches_lsb_fault
  COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/check/fault_lsb/tb.vvp -DCONFIG=grey_s428w
          -DWORK=${ICARUS_DIR}/check/fault_lsb -DSCENARIO=mixed -DSEED=3 -DFAULT=lsb@17
          -DEXPECT_MISMATCH_Y=17 -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
add_test(NAME icarus_catches_stall_fault
  COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/check/fault_stall/tb.vvp -DCONFIG=grey_s428w
          -DWORK=${ICARUS_DIR}/check/fault_stall -DSCENARIO=mixed -DSEED=4 -DFAULT=stall@23
          -DEXPECT_MISMATCH_Y=23 -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
# The testbench declares every shade_unit parameter with its default and passes it on; the
# same check fails for a parameter shade_unit gains (INJECT adds one to shade_unit's list).
set(_tb_params ${CMAKE_COMMAND} -DRTL_TOP=${CMAKE_SOURCE_DIR}/rtl/shade_unit.sv -DTB=${ICARUS_TB})
add_test(NAME icarus_tb_params
  COMMAND ${_tb_params} -P ${CMAKE_SOURCE_DIR}/sim/icarus/tb_params_check.cmake)
add_test(NAME icarus_tb_params_catches_new_parameter
  COMMAND ${_tb_params} -DINJECT=NEW_SHADE_UNIT_PARAMETER -P ${CMAKE_SOURCE_DIR}/sim/icarus/tb_params_check.cmake)
set_tests_properties(icarus_tb_params_catches_new_parameter PROPERTIES
  PASS_REGULAR_EXPRESSION "shade_unit parameter NEW_SHADE_UNIT_PARAMETER \\(default 0\\) is not declared by tb_shade_unit")
# $readmemh of a missing file only warns: the testbench must stop instead.
add_test(NAME icarus_tb_compile_grey_s428w
  COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/tb_grey_s428w.vvp -DCONFIG=grey_s428w -DWORK=${ICARUS_DIR}
          -DCOMPILE_ONLY=ON -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
set_tests_properties(icarus_tb_compile_grey_s428w PROPERTIES FIXTURES_SETUP icarus_tb_grey)
add_test(NAME icarus_tb_missing_words
  COMMAND ${VVP} -n ${ICARUS_DIR}/tb_grey_s428w.vvp +words=${ICARUS_DIR}/no-such-file.hex)
set_tests_properties(icarus_tb_missing_words PROPERTIES
  PASS_REGULAR_EXPRESSION "no-such-file.hex: cannot open the file" FIXTURES_REQUIRED icarus_tb_grey)
# The synthesis views against `*` (tests/rtl/synthesis_view_check.cmake), each with the same
# check on a copy with a deliberate slip, which must fail: span_setup's radix-4 Booth product
# exhaustively (every 10-bit t, every d of 1..7 bits, wrapping and exact units), and W_m's
# squarer (every base of B = 2..12 and 16, 20,004 of B = 30).
set(_view_check ${CMAKE_COMMAND} -DIVERILOG=${IVERILOG} -DVVP=${VVP} -DSRC=${CMAKE_SOURCE_DIR})
foreach(view booth square)
  set(_name wpow_square)
  if(view STREQUAL "booth")
    set(_name span_setup_booth)
  endif()
  add_test(NAME icarus_${_name}
    COMMAND ${_view_check} -DVIEW=${view} -DWORK=${ICARUS_DIR}/${view}
            -P ${CMAKE_SOURCE_DIR}/tests/rtl/synthesis_view_check.cmake)
  add_test(NAME icarus_${_name}_catches_broken
    COMMAND ${_view_check} -DVIEW=${view} -DWORK=${ICARUS_DIR}/${view}_broken -DBREAK=ON
            -P ${CMAKE_SOURCE_DIR}/tests/rtl/synthesis_view_check.cmake)
endforeach()
# fixed_sat exhaustively: every input of 120 small parameter combinations (both generate views)
# against the overflow rule's closed form, and the same check on a copy with a broken clamp,
# which must fail. None of the coverage runs' units elaborates g_fits (every instance narrows).
set(_fixed_sat_check ${CMAKE_SOURCE_DIR}/tests/rtl/fixed_sat_check.py ${CMAKE_SOURCE_DIR}
    ${IVERILOG} ${VVP})
add_test(NAME icarus_fixed_sat_exhaustive COMMAND ${_fixed_sat_check} ${ICARUS_DIR}/fixed_sat)
add_test(NAME icarus_fixed_sat_catches_broken
  COMMAND ${_fixed_sat_check} ${ICARUS_DIR}/fixed_sat_broken --break)
# Every parameter check of rtl/ at its edges: shade_unit elaborates at each legal
# extreme of the model's ranges and stops with that check's message one step past it.
add_test(NAME icarus_param_extremes
  COMMAND ${CMAKE_SOURCE_DIR}/tests/rtl/param_extremes.py ${SHADESIM_CLI} ${IVERILOG} ${VVP}
          ${CMAKE_SOURCE_DIR} ${ICARUS_DIR}/param_extremes)
