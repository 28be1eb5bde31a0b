# Icarus Verilog as an independent simulator of the same RTL (rtl/*.sv): the testbench
# sim/icarus/tb_shade_unit.sv replays a command stream's words and writes its pixels, which must
# equal the bit-accurate model's bit for bit; scripts/bench-cosim times it against the Verilator
# backends. Included after cmake/rtl.cmake (it uses RTL_SOURCES and the RTL_CONFIG_* variables).
#
# The same file, run as a script (cmake -DICARUS_CHECK=ON ... -P cmake/icarus.cmake), is one
# check: random stream -> hex words + model pixels -> vvp -> compare (and, given the Verilator
# executable, the cycle count against it).

if(CMAKE_SCRIPT_MODE_FILE)
  if(NOT ICARUS_CHECK)
    message(FATAL_ERROR "icarus.cmake: run as a script only with -DICARUS_CHECK=ON")
  endif()
  foreach(var TOOL VVP TB SPEC WORK SCENARIO SEED)
    if(NOT DEFINED ${var})
      message(FATAL_ERROR "icarus check: -D${var}=... is required")
    endif()
  endforeach()
  file(MAKE_DIRECTORY ${WORK})
  set(stem ${WORK}/${SCENARIO}_${SEED})
  function(_icarus_step what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "icarus check: ${what} failed (${rc}):\n  ${ARGN}\n${out}${err}")
    endif()
    set(step_out "${out}" PARENT_SCOPE)
  endfunction()
  _icarus_step("random stream" ${TOOL} random --rtl-config ${SPEC} --scenario ${SCENARIO} --seed ${SEED} --save ${stem}.cmds)
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
  if(COSIM)
    _icarus_step("${COSIM}" ${COSIM} --config ${CONFIG} --stream ${stem}.cmds --gap-pct 0 --stall-pct 0)
    if(NOT step_out MATCHES "cycles=([0-9]+)")
      message(FATAL_ERROR "icarus check: ${COSIM} printed no cycle count:\n${step_out}")
    endif()
    if(NOT CMAKE_MATCH_1 EQUAL icarus_cycles)
      message(FATAL_ERROR "icarus check: Icarus took ${icarus_cycles} cycles, ${COSIM} ${CMAKE_MATCH_1} (stream ${stem}.cmds)")
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
if(NOT TARGET shadesim_harness OR NOT RTL_CONFIG_NAMES)
  message(WARNING "cmake/rtl.cmake defined no RTL configurations: Icarus checks are skipped")
  return()
endif()

add_executable(icarus_stream_tool ${CMAKE_SOURCE_DIR}/sim/icarus/stream_tool.cpp)
target_link_libraries(icarus_stream_tool PRIVATE shadesim_harness CLI11::CLI11)

# Per configuration: the testbench compiled with its parameters (icarus/tb_NAME.vvp) and its
# fields as one comma-separated line (icarus/NAME.rtl-config) for icarus_stream_tool and
# scripts/bench-cosim.
set(ICARUS_DIR ${CMAKE_BINARY_DIR}/icarus)
set(ICARUS_TB ${CMAKE_SOURCE_DIR}/sim/icarus/tb_shade_unit.sv)
file(READ ${ICARUS_TB} _icarus_tb_text)
foreach(name ${RTL_CONFIG_NAMES})
  set(params "")
  foreach(p ${RTL_CONFIG_${name}_PARAMS})
    # iverilog -P sets parameters of the root module only: the testbench must mirror each of
    # shade_unit's (an unknown -P is only a warning, and the RTL would silently get its default).
    string(REGEX REPLACE "^-G([A-Za-z0-9_]+)=.*$" "\\1" pname "${p}")
    if(NOT _icarus_tb_text MATCHES "parameter int ${pname} ")
      message(FATAL_ERROR "cmake/icarus.cmake: configuration ${name} sets shade_unit parameter ${pname}, "
                          "which sim/icarus/tb_shade_unit.sv does not declare and pass on; add it there")
    endif()
    string(REGEX REPLACE "^-G" "-Ptb_shade_unit." p "${p}")
    list(APPEND params ${p})
  endforeach()
  string(REGEX REPLACE "^X\\((.*)\\)$" "\\1" spec "${RTL_CONFIG_${name}_ENTRY}")
  string(REPLACE "\"" "" spec "${spec}")
  string(REPLACE " " "" spec "${spec}")
  file(WRITE ${ICARUS_DIR}/${name}.rtl-config.new "${spec}\n")
  configure_file(${ICARUS_DIR}/${name}.rtl-config.new ${ICARUS_DIR}/${name}.rtl-config COPYONLY)
  set(RTL_CONFIG_${name}_SPEC "${spec}")
  add_custom_command(
    OUTPUT ${ICARUS_DIR}/tb_${name}.vvp
    COMMAND ${IVERILOG} -g2012 -s tb_shade_unit ${params} -o ${ICARUS_DIR}/tb_${name}.vvp
            ${RTL_SOURCES} ${ICARUS_TB}
    DEPENDS ${RTL_SOURCES} ${ICARUS_TB}
    COMMENT "Icarus: tb_shade_unit for ${name}"
    VERBATIM)
  add_custom_target(icarus_tb_${name} ALL DEPENDS ${ICARUS_DIR}/tb_${name}.vvp)
endforeach()

# Icarus pixels = model pixels, bit for bit, on random streams (and cycles = the Verilator C++
# backend's); the check must catch the deliberate LSB fault on its scanline.
# The RGB/two-light build is ~5x slower under Icarus: fewer scenarios there (CI budget).
set(_icarus_check ${CMAKE_COMMAND} -DICARUS_CHECK=ON -DTOOL=$<TARGET_FILE:icarus_stream_tool> -DVVP=${VVP})
set(_icarus_scenarios_grey_s428w mixed short long switch)
set(_icarus_scenarios_rgb2_s320s mixed long)
set(_icarus_scenarios_grey_p4 mixed short)
set(_icarus_scenarios_grey_p4_q2 mixed short)
foreach(name grey_s428w rgb2_s320s grey_p4 grey_p4_q2)
  if(NOT DEFINED RTL_CONFIG_${name}_SPEC)
    continue()
  endif()
  foreach(scenario ${_icarus_scenarios_${name}})
    add_test(NAME icarus_model_${name}_${scenario}
      COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/tb_${name}.vvp "-DSPEC=${RTL_CONFIG_${name}_SPEC}"
              -DWORK=${ICARUS_DIR}/check/${name} -DSCENARIO=${scenario} -DSEED=11
              -DCOSIM=$<TARGET_FILE:rtl_cosim_cpp> -DCONFIG=${name} -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
  endforeach()
endforeach()
if(DEFINED RTL_CONFIG_fault_lsb_SPEC)
  add_test(NAME icarus_catches_lsb_fault
    COMMAND ${_icarus_check} -DTB=${ICARUS_DIR}/tb_fault_lsb.vvp "-DSPEC=${RTL_CONFIG_fault_lsb_SPEC}"
            -DWORK=${ICARUS_DIR}/check/fault_lsb -DSCENARIO=mixed -DSEED=3 -DEXPECT_MISMATCH_Y=17
            -P ${CMAKE_SOURCE_DIR}/cmake/icarus.cmake)
endif()
# $readmemh of a missing file only warns: the testbench must stop instead.
if(DEFINED RTL_CONFIG_grey_s428w_SPEC)
  add_test(NAME icarus_tb_missing_words
    COMMAND ${VVP} -n ${ICARUS_DIR}/tb_grey_s428w.vvp +words=${ICARUS_DIR}/no-such-file.hex)
  set_tests_properties(icarus_tb_missing_words PROPERTIES
    PASS_REGULAR_EXPRESSION "no-such-file.hex: cannot open the file")
endif()
