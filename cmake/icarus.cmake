# Icarus Verilog as an independent simulator of the same RTL (rtl/*.sv): the testbench
# sim/icarus/tb_shade_unit.sv replays a command stream's words and writes its pixels, which must
# equal the bit-accurate model's bit for bit; scripts/bench-cosim times it against the Verilator
# backends. Included after cmake/rtl.cmake (it uses RTL_SOURCES, RTL_CACHE and SHADESIM_CLI).
#
# The testbench of a named build is compiled with the build's parameters, which shadesim prints
# from the one mapping (shadesim rtl-params --tool iverilog); iverilog -P sets parameters of the
# root module only, so each must be one the testbench declares and passes on (an unknown -P is
# only a warning, and the RTL would silently get its default): the check fails otherwise.
#
# The same file, run as a script (cmake -DICARUS_CHECK=ON ... -P cmake/icarus.cmake), is one
# check: testbench -> random stream -> hex words + model pixels -> vvp -> compare (and, given
# shadesim, the cycle count against the Verilator C++ backend's). With -DCOMPILE_ONLY=ON it
# only compiles the testbench (scripts/bench-cosim).

if(CMAKE_SCRIPT_MODE_FILE)
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
    if(NOT tb_text MATCHES "parameter int ${pname} ")
      message(FATAL_ERROR "icarus check: ${CONFIG} sets shade_unit parameter ${pname}, which "
                          "sim/icarus/tb_shade_unit.sv does not declare and pass on; add it there")
    endif()
  endforeach()
  string(REPLACE "," ";" rtl_sources "${RTL}")
  _icarus_step("iverilog" ${IVERILOG} -g2012 -s tb_shade_unit ${params} -o ${TB} ${rtl_sources} ${TB_SRC})
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
  _icarus_step("export" ${TOOL} export ${stem}.cmds --hex ${stem}.hex --pixels ${stem}.expected.txt)
  _icarus_step("vvp" ${VVP} -n ${TB} +words=${stem}.hex +pixels=${stem}.icarus.txt)
  message(STATUS "${step_out}")
  if(NOT step_out MATCHES "cycles=([0-9]+)")
    message(FATAL_ERROR "icarus check: the testbench printed no cycle count:\n${step_out}")
  endif()
  set(icarus_cycles ${CMAKE_MATCH_1})
  execute_process(COMMAND ${TOOL} compare ${stem}.expected.txt ${stem}.icarus.txt
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(EXPECT_MISMATCH_Y)
    # A deliberately broken RTL build: the comparison must fail, first on that scanline.
    if(rc EQUAL 0)
      message(FATAL_ERROR "icarus check: expected a pixel mismatch at y=${EXPECT_MISMATCH_Y}, but the pixels are identical")
    endif()
    if(NOT err MATCHES "expected \"[0-9]+ ${EXPECT_MISMATCH_Y} ")
      message(FATAL_ERROR "icarus check: expected the first mismatch at y=${EXPECT_MISMATCH_Y}, got:\n${err}")
    endif()
    message(STATUS "the deliberate fault was caught where expected: ${err}")
    return()
  endif()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "icarus check: Icarus pixels differ from the bit-accurate model's (stream ${stem}.cmds):\n${err}")
  endif()
  message(STATUS "${out}")
  if(CACHE)
    _icarus_step("shadesim cosim" ${SHADESIM} cosim --backend cpp --cache ${CACHE} --config ${CONFIG}
                 --stream ${stem}.cmds --gap-pct 0 --stall-pct 0)
    if(NOT step_out MATCHES "cycles=([0-9]+)")
      message(FATAL_ERROR "icarus check: shadesim cosim printed no cycle count:\n${step_out}")
    endif()
    if(NOT CMAKE_MATCH_1 EQUAL icarus_cycles)
      message(FATAL_ERROR "icarus check: Icarus took ${icarus_cycles} cycles, Verilator ${CMAKE_MATCH_1} (stream ${stem}.cmds)")
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
target_link_libraries(icarus_stream_tool PRIVATE shadesim_harness CLI11::CLI11)

set(ICARUS_DIR ${CMAKE_BINARY_DIR}/icarus)
set(ICARUS_TB ${CMAKE_SOURCE_DIR}/sim/icarus/tb_shade_unit.sv)
string(REPLACE ";" "," _rtl_list "${RTL_SOURCES}")
# Icarus pixels = model pixels, bit for bit, on random streams (and cycles = the Verilator C++
# backend's); the check must catch the deliberate LSB fault on its scanline.
# The RGB/two-light build is ~5x slower under Icarus: fewer scenarios there (CI budget).
set(_icarus_check ${CMAKE_COMMAND} -DICARUS_CHECK=ON -DSHADESIM=${SHADESIM_CLI} -DIVERILOG=${IVERILOG}
    -DTB_SRC=${ICARUS_TB} -DRTL=${_rtl_list} -DTOOL=$<TARGET_FILE:icarus_stream_tool> -DVVP=${VVP}
    -DBUILDS=${CMAKE_SOURCE_DIR}/sim/harness/builds.json)
set(_icarus_scenarios_grey_s428w mixed short long switch)
set(_icarus_scenarios_rgb2_s320s mixed long)
set(_icarus_scenarios_grey_p4 mixed short)
set(_icarus_scenarios_grey_p4_q2 mixed short)
set(_icarus_scenarios_grey_pack_p4_q2 mixed short)
set(_icarus_scenarios_grey_p4_q2_l4_m2 mixed short)
foreach(name grey_s428w rgb2_s320s grey_p4 grey_p4_q2 grey_pack_p4_q2 grey_p4_q2_l4_m2)
  foreach(scenario ${_icarus_scenarios_${name}})
    add_test(NAME icarus_model_${name}_${scenario}
      COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/check/${name}/tb_${scenario}.vvp -DCONFIG=${name}
              -DWORK=${ICARUS_DIR}/check/${name} -DSCENARIO=${scenario} -DSEED=11
              -DCACHE=${RTL_CACHE} -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
  endforeach()
endforeach()
add_test(NAME icarus_catches_lsb_fault
  COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/check/fault_lsb/tb.vvp -DCONFIG=fault_lsb
          -DWORK=${ICARUS_DIR}/check/fault_lsb -DSCENARIO=mixed -DSEED=3 -DEXPECT_MISMATCH_Y=17
          -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
# $readmemh of a missing file only warns: the testbench must stop instead.
add_test(NAME icarus_tb_compile_grey_s428w
  COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/tb_grey_s428w.vvp -DCONFIG=grey_s428w -DWORK=${ICARUS_DIR}
          -DCOMPILE_ONLY=ON -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
set_tests_properties(icarus_tb_compile_grey_s428w PROPERTIES FIXTURES_SETUP icarus_tb_grey)
add_test(NAME icarus_tb_missing_words
  COMMAND ${VVP} -n ${ICARUS_DIR}/tb_grey_s428w.vvp +words=${ICARUS_DIR}/no-such-file.hex)
set_tests_properties(icarus_tb_missing_words PROPERTIES
  PASS_REGULAR_EXPRESSION "no-such-file.hex: cannot open the file" FIXTURES_REQUIRED icarus_tb_grey)
