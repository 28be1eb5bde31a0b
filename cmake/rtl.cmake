# RTL (rtl/*.sv) checks and the Verilator co-simulation harness (sim/harness/).
#
# Each RTL configuration is Verilated once per backend, straight into the one executable that
# uses it (rtl_cosim_cpp: Verilator C++; rtl_cosim_sc: Verilator SystemC); every co-simulation
# test and the benchmark run those two executables with different arguments.
find_package(verilator 5 HINTS $ENV{VERILATOR_ROOT})
if(NOT verilator_FOUND)
  message(WARNING "Verilator not found: RTL co-simulation targets and tests are skipped")
  return()
endif()
find_program(IVERILOG iverilog)
find_program(YOSYS yosys)

set(RTL_DIR ${CMAKE_SOURCE_DIR}/rtl)
# Dependency order (leaves first) for tools that want it.
set(RTL_SOURCES
  ${RTL_DIR}/shade_pkg.sv ${RTL_DIR}/fixed_round.sv ${RTL_DIR}/fixed_sat.sv ${RTL_DIR}/span_setup.sv
  ${RTL_DIR}/series_engine.sv ${RTL_DIR}/pixel_combine.sv
  ${RTL_DIR}/exponent_lut.sv ${RTL_DIR}/schlick_divider.sv ${RTL_DIR}/wpow_unit.sv
  ${RTL_DIR}/specular_slot.sv ${RTL_DIR}/shade_unit.sv)

# Fixed-point format text ("s4.28:rnd:wrap", as FixedFormat::to_string writes it) -> parameters.
function(_rtl_format_params prefix text out)
  if(NOT text MATCHES "^([su])(-?[0-9]+)\\.([0-9]+)(.*)$")
    message(FATAL_ERROR "rtl config: cannot read fixed-point format '${text}' for ${prefix}")
  endif()
  math(EXPR wl "${CMAKE_MATCH_2} + ${CMAKE_MATCH_3}")
  set(params -G${prefix}_WL=${wl} -G${prefix}_IWL=${CMAKE_MATCH_2})
  set(suffix "${CMAKE_MATCH_4}")
  if(prefix STREQUAL "SERIES")
    set(quant 0)
    set(overflow 0)
    if(suffix MATCHES ":rnd")
      set(quant 1)
    endif()
    if(suffix MATCHES ":wrap")
      set(overflow 1)
    endif()
    list(APPEND params -GSERIES_QUANT=${quant} -GSERIES_OVERFLOW=${overflow})
  endif()
  set(${out} ${params} PARENT_SCOPE)
endfunction()

# A specular unit's fields ("addr_bits=10 index=nearest", the JSON names of its config) ->
# parameters with the unit's prefix (LUT_ADDR_BITS=10 LUT_INDEX=1). Host-only fields (LUT
# addressing and shared range, fit objectives) shape the stream, not the hardware: no parameter.
function(_rtl_unit_params name kind text out)
  set(params "")
  string(TOUPPER "${kind}" prefix)
  separate_arguments(pairs UNIX_COMMAND "${text}")
  foreach(pair ${pairs})
    if(NOT pair MATCHES "^([a-z_0-9]+)=(.+)$")
      message(FATAL_ERROR "rtl config ${name}: UNIT entry '${pair}': expected key=value")
    endif()
    set(key ${CMAKE_MATCH_1})
    set(value ${CMAKE_MATCH_2})
    if(key STREQUAL "addressing" OR key STREQUAL "shared_range_log2" OR key STREQUAL "fit")
      continue()
    endif()
    if(key STREQUAL "index")
      set(map_truncate 0)
      set(map_nearest 1)
    elseif(key STREQUAL "timing")
      set(map_pipelined 0)
      set(map_iterative 1)
    endif()
    if(key STREQUAL "index" OR key STREQUAL "timing")
      if(NOT DEFINED map_${value})
        message(FATAL_ERROR "rtl config ${name}: UNIT ${key}=${value} is not a known value")
      endif()
      set(value ${map_${value}})
    elseif(NOT value MATCHES "^[0-9]+$")
      message(FATAL_ERROR "rtl config ${name}: UNIT ${key}=${value}: expected a non-negative integer")
    endif()
    string(TOUPPER "${key}" ukey)
    list(APPEND params -G${prefix}_${ukey}=${value})
  endforeach()
  set(${out} ${params} PARENT_SCOPE)
endfunction()

# One configuration: the UnitConfig fields as text (the harness parses the same strings into a
# UnitConfig, so CMake and C++ cannot disagree), plus the deliberate-fault rows (-1 = none).
# Ideal-unit configurations go to RTL_CONFIG_NAMES; configurations with a hardware specular unit
# (UNIT = its fields) to RTL_SPECULAR_CONFIG_NAMES, kept apart because their extra parameters are
# not (yet) mirrored by the Icarus testbench (cmake/icarus.cmake iterates RTL_CONFIG_NAMES).
# RTL_CONFIG_<name>_ENTRY keeps its 12 fields (read by cmake/icarus.cmake); the co-simulation
# executables use RTL_CONFIG_<name>_COSIM_ENTRY, which adds UNIT.
set(RTL_CONFIG_NAMES "")
set(RTL_SPECULAR_CONFIG_NAMES "")
function(rtl_config name)
  cmake_parse_arguments(C "" "CHANNELS;LIGHTS;XY_BITS;COEF;SERIES;SPEC_COLOUR;OUT_BITS;SPECULAR;SPECULAR_OUT;UNIT;FAULT_LSB_ROW;FAULT_STALL_ROW;PORT_WORDS;TRI_QUEUE" "BACKENDS" ${ARGN})
  foreach(field FAULT_LSB_ROW FAULT_STALL_ROW)
    if(NOT DEFINED C_${field})
      set(C_${field} -1)
    endif()
  endforeach()
  # Throughput structure (UnitConfig::port_words ...): 1 unless given.
  foreach(field PORT_WORDS TRI_QUEUE)
    if(NOT DEFINED C_${field})
      set(C_${field} 1)
    endif()
  endforeach()
  set(kinds ideal lut schlick wpow)
  list(FIND kinds ${C_SPECULAR} kind)
  if(kind LESS 0)
    message(FATAL_ERROR "rtl config ${name}: SPECULAR must be one of ${kinds}, got '${C_SPECULAR}'")
  endif()
  _rtl_format_params(COEF ${C_COEF} coef)
  _rtl_format_params(SERIES ${C_SERIES} series)
  _rtl_format_params(SPEC_COLOUR ${C_SPEC_COLOUR} spec_colour)
  _rtl_format_params(SPECULAR_OUT ${C_SPECULAR_OUT} spec_out)
  set(params -GCHANNELS=${C_CHANNELS} -GLIGHTS=${C_LIGHTS} -GXY_BITS=${C_XY_BITS}
      ${coef} ${series} ${spec_colour} -GOUT_BITS=${C_OUT_BITS} -GSPECULAR_KIND=${kind}
      ${spec_out} -GPORT_WORDS=${C_PORT_WORDS} -GTRI_QUEUE=${C_TRI_QUEUE}
      -GFAULT_LSB_ROW=${C_FAULT_LSB_ROW} -GFAULT_STALL_ROW=${C_FAULT_STALL_ROW})
  if(kind GREATER 0)
    set(quant 0)
    set(overflow 0)
    if(C_SPECULAR_OUT MATCHES ":rnd")
      set(quant 1)
    endif()
    if(C_SPECULAR_OUT MATCHES ":wrap")
      set(overflow 1)
    endif()
    _rtl_unit_params(${name} ${C_SPECULAR} "${C_UNIT}" unit)
    list(APPEND params -GSPECULAR_OUT_QUANT=${quant} -GSPECULAR_OUT_OVERFLOW=${overflow} ${unit})
  elseif(C_UNIT)
    message(FATAL_ERROR "rtl config ${name}: UNIT given for the ideal unit, which has no parameters")
  endif()
  set(RTL_CONFIG_${name}_PARAMS ${params} PARENT_SCOPE)
  set(RTL_CONFIG_${name}_BACKENDS ${C_BACKENDS} PARENT_SCOPE)
  set(head "${name}, ${C_CHANNELS}, ${C_LIGHTS}, ${C_XY_BITS}, \"${C_COEF}\", \"${C_SERIES}\", \"${C_SPEC_COLOUR}\", ${C_OUT_BITS}, \"${C_SPECULAR}\", \"${C_SPECULAR_OUT}\", ${C_FAULT_LSB_ROW}, ${C_FAULT_STALL_ROW}")
  set(head "${head}, ${C_PORT_WORDS}, ${C_TRI_QUEUE}")
  set(RTL_CONFIG_${name}_ENTRY "X(${head})" PARENT_SCOPE)
  set(RTL_CONFIG_${name}_COSIM_ENTRY "X(${head}, \"${C_UNIT}\")" PARENT_SCOPE)
  if(kind GREATER 0)
    set(RTL_SPECULAR_CONFIG_NAMES ${RTL_SPECULAR_CONFIG_NAMES} ${name} PARENT_SCOPE)
  else()
    set(RTL_CONFIG_NAMES ${RTL_CONFIG_NAMES} ${name} PARENT_SCOPE)
  endif()
endfunction()

# The default configurations: two width sets (wrap vs saturate, truncate vs round, grey vs RGB
# with two lights), and the deliberately broken builds the harness must catch.
rtl_config(grey_s428w CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 BACKENDS "cpp;sc")
rtl_config(rgb2_s320s CHANNELS 3 LIGHTS 2 XY_BITS 11 COEF s3.30:rnd SERIES s3.20:rnd
           SPEC_COLOUR u1.12:rnd OUT_BITS 10 SPECULAR ideal SPECULAR_OUT u1.16 BACKENDS "cpp;sc")
rtl_config(fault_lsb CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16
           FAULT_LSB_ROW 17 BACKENDS "cpp")
rtl_config(fault_stall CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16
           FAULT_STALL_ROW 23 BACKENDS "cpp")
# Throughput (issue 8): wider command ports, on both width sets; the faults on a wide port.
rtl_config(grey_p2 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 2 BACKENDS "cpp")
rtl_config(grey_p4 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 4 BACKENDS "cpp;sc")
rtl_config(rgb2_p8 CHANNELS 3 LIGHTS 2 XY_BITS 11 COEF s3.30:rnd SERIES s3.20:rnd
           SPEC_COLOUR u1.12:rnd OUT_BITS 10 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 8 BACKENDS "cpp")
rtl_config(grey_p4_q2 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 4 TRI_QUEUE 2
           BACKENDS "cpp;sc")
rtl_config(rgb2_p8_q3 CHANNELS 3 LIGHTS 2 XY_BITS 11 COEF s3.30:rnd SERIES s3.20:rnd
           SPEC_COLOUR u1.12:rnd OUT_BITS 10 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 8 TRI_QUEUE 3
           BACKENDS "cpp")
rtl_config(grey_p1_q2 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 TRI_QUEUE 2 BACKENDS "cpp")
rtl_config(fault_lsb_p4 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 4
           FAULT_LSB_ROW 17 BACKENDS "cpp")
rtl_config(fault_stall_p4 CHANNELS 1 LIGHTS 1 XY_BITS 12 COEF s4.32:rnd SERIES s4.28:wrap
           SPEC_COLOUR u1.12:rnd OUT_BITS 8 SPECULAR ideal SPECULAR_OUT u1.16 PORT_WORDS 4
           FAULT_STALL_ROW 23 BACKENDS "cpp")

# The specular-unit regression (milestone 2): RGB with 2 lights (every shipped scene fits: the
# encoder pads lights and repeats grey channels) x {per-exponent LUT, Schlick iterative, Schlick
# pipelined, W_m m=16} x two width sets: "d" = UnitConfig's defaults (coef s4.32:rnd:wrap,
# series s4.28 truncate+wrap, spec colour u1.12:rnd, out 8, xy 12, specular out u1.16, unit
# defaults) and "n" = narrower (coef s3.30:rnd, series s3.20 round+saturate, spec colour
# u1.10:rnd, out 8, xy 11, specular out u1.12, smaller units).
set(_rtl_d CHANNELS 3 LIGHTS 2 XY_BITS 12 COEF s4.32:rnd:wrap SERIES s4.28:wrap SPEC_COLOUR u1.12:rnd
           OUT_BITS 8 SPECULAR_OUT u1.16)
set(_rtl_n CHANNELS 3 LIGHTS 2 XY_BITS 11 COEF s3.30:rnd:wrap SERIES s3.20:rnd SPEC_COLOUR u1.10:rnd
           OUT_BITS 8 SPECULAR_OUT u1.12)
rtl_config(lut_d ${_rtl_d} SPECULAR lut UNIT "addr_bits=10 entry_bits=8" BACKENDS "cpp;sc")
rtl_config(schlick_iter_d ${_rtl_d} SPECULAR schlick UNIT "quotient_bits=16 operand_bits=24 timing=iterative" BACKENDS "cpp;sc")
rtl_config(schlick_pipe_d ${_rtl_d} SPECULAR schlick UNIT "quotient_bits=16 operand_bits=24 timing=pipelined" BACKENDS "cpp;sc")
rtl_config(wpow16_d ${_rtl_d} SPECULAR wpow UNIT "max_m=16 base_bits=16 timing=pipelined" BACKENDS "cpp;sc")
rtl_config(lut_n ${_rtl_n} SPECULAR lut UNIT "addr_bits=8 entry_bits=8 interp_bits=4 index=nearest" BACKENDS "cpp;sc")
rtl_config(schlick_iter_n ${_rtl_n} SPECULAR schlick UNIT "quotient_bits=12 operand_bits=16 timing=iterative" BACKENDS "cpp;sc")
rtl_config(schlick_pipe_n ${_rtl_n} SPECULAR schlick UNIT "quotient_bits=12 operand_bits=16 timing=pipelined" BACKENDS "cpp;sc")
rtl_config(wpow16_n ${_rtl_n} SPECULAR wpow UNIT "max_m=16 base_bits=12 timing=iterative" BACKENDS "cpp;sc")

# ---- plain C++ harness: scoreboard, random streams (stimulus and cycle model are in model/) ----
add_library(shadesim_harness STATIC
  ${CMAKE_SOURCE_DIR}/sim/harness/scoreboard.cpp
  ${CMAKE_SOURCE_DIR}/sim/harness/random_stream.cpp
  ${CMAKE_SOURCE_DIR}/sim/harness/rtl_config.cpp)
target_link_libraries(shadesim_harness PUBLIC shadesim_model)

# ---- Verilated executables --------------------------------------------------------------------
# SystemC as Debian packages it (pkg-config), for verilator_link_systemc.
if(NOT TARGET Verilator::systemc)
  add_library(Verilator::systemc INTERFACE IMPORTED)
  target_link_libraries(Verilator::systemc INTERFACE PkgConfig::SYSTEMC)
endif()

# rtl_cosim_cpp_trace: the C++ backend with FST tracing compiled in (--waves); a separate build
# because tracing support slows every Verilated model, traced or not.
foreach(backend cpp sc cpp_trace)
  set(exe rtl_cosim_${backend})
  set(entries "")
  set(includes "")
  add_executable(${exe} ${CMAKE_SOURCE_DIR}/sim/harness/cosim_main.cpp)
  foreach(name ${RTL_CONFIG_NAMES} ${RTL_SPECULAR_CONFIG_NAMES})
    # SHADESIM_RTL_ONLY (a list of names, empty by default): Verilate only these, to save build
    # time on a development machine; the tests of the others then fail to find their build.
    if(SHADESIM_RTL_ONLY AND NOT name IN_LIST SHADESIM_RTL_ONLY)
      continue()
    endif()
    set(want ${backend})
    if(backend STREQUAL "cpp_trace")
      set(want cpp)
    endif()
    if(NOT want IN_LIST RTL_CONFIG_${name}_BACKENDS)
      continue()
    endif()
    set(extra "")
    if(backend STREQUAL "sc")
      set(extra SYSTEMC)
    elseif(backend STREQUAL "cpp_trace")
      set(extra TRACE_FST)
    endif()
    verilate(${exe} ${extra}
      SOURCES ${RTL_SOURCES}
      TOP_MODULE shade_unit
      PREFIX V${name}
      DIRECTORY ${CMAKE_BINARY_DIR}/verilated/${backend}/${name}
      VERILATOR_ARGS ${RTL_CONFIG_${name}_PARAMS} --x-assign fast --x-initial fast -O3)
    string(APPEND entries "${RTL_CONFIG_${name}_COSIM_ENTRY}\n")
    string(APPEND includes "#include \"V${name}.h\"\n")
  endforeach()
  file(WRITE ${CMAKE_BINARY_DIR}/verilated/${backend}/rtl_configs.inc.new
       "// Generated by cmake/rtl.cmake: the configurations Verilated into ${exe}.\n${includes}#define SHADESIM_RTL_CONFIGS(X) \\\n")
  string(REPLACE "\n" " \\\n" entries_cont "${entries}")
  file(APPEND ${CMAKE_BINARY_DIR}/verilated/${backend}/rtl_configs.inc.new "${entries_cont}\n")
  configure_file(${CMAKE_BINARY_DIR}/verilated/${backend}/rtl_configs.inc.new
                 ${CMAKE_BINARY_DIR}/verilated/${backend}/rtl_configs.inc COPYONLY)
  target_include_directories(${exe} PRIVATE ${CMAKE_SOURCE_DIR} ${CMAKE_BINARY_DIR}/verilated/${backend})
  target_link_libraries(${exe} PRIVATE shadesim_harness CLI11::CLI11)
  if(backend STREQUAL "sc")
    target_compile_definitions(${exe} PRIVATE SHADESIM_COSIM_SYSTEMC=1)
    verilator_link_systemc(${exe})
  elseif(backend STREQUAL "cpp_trace")
    target_compile_definitions(${exe} PRIVATE SHADESIM_COSIM_TRACE=1)
    # Only ever re-runs one failing job: build time matters more than speed here.
    target_compile_options(${exe} PRIVATE -O1)
  endif()
endforeach()

# ---- tests --------------------------------------------------------------------------------------
# Static checks on the RTL: lint, Icarus, Yosys (no latches).
add_test(NAME rtl_lint_grey_s428w
  COMMAND verilator --lint-only -Wall ${RTL_CONFIG_grey_s428w_PARAMS} --top-module shade_unit ${RTL_SOURCES})
add_test(NAME rtl_lint_rgb2_s320s
  COMMAND verilator --lint-only -Wall ${RTL_CONFIG_rgb2_s320s_PARAMS} --top-module shade_unit ${RTL_SOURCES})
if(IVERILOG)
  add_test(NAME rtl_iverilog
    COMMAND ${IVERILOG} -g2012 -Wall -s shade_unit -o ${CMAKE_BINARY_DIR}/rtl_iverilog.vvp ${RTL_SOURCES})
endif()
if(YOSYS)
  add_test(NAME rtl_yosys_no_latch
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys.log ${RTL_SOURCES})
  # shade_unit's slot glue: the metadata delay line (pipelined W_m, latency 3) and the pending
  # register of an iterative unit (W_m iterative); small units keep synthesis quick.
  foreach(timing 0 1)
    add_test(NAME rtl_yosys_no_latch_wpow_timing${timing}
      COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_wpow${timing}.log ${RTL_SOURCES})
    set_tests_properties(rtl_yosys_no_latch_wpow_timing${timing} PROPERTIES
      ENVIRONMENT "YOSYS_CHPARAM=-set SPECULAR_KIND 3 -set WPOW_MAX_M 4 -set WPOW_BASE_BITS 8 -set WPOW_TIMING ${timing}")
  endforeach()
  # The wide port's beat decoder and the triangle queue's banks and span queue.
  add_test(NAME rtl_yosys_no_latch_port4_queue3
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_p4q3.log ${RTL_SOURCES})
  set_tests_properties(rtl_yosys_no_latch_port4_queue3 PROPERTIES
    ENVIRONMENT "YOSYS_CHPARAM=-set PORT_WORDS 4 -set TRI_QUEUE 3")
endif()

# Co-simulation: every scenario, several seeds, both backends, both width sets.
foreach(name grey_s428w rgb2_s320s)
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND rtl_cosim_cpp --config ${name} --scenario all --seed 1 --runs 3
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  foreach(scenario mixed long short slow maxbp switch tiny)
    add_test(NAME rtl_cosim_sc_${name}_${scenario}
      COMMAND rtl_cosim_sc --config ${name} --scenario ${scenario} --seed 7
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endforeach()
endforeach()
# Wider command ports and triangle queues (issue 8): every scenario, three seeds; SystemC on
# the four-word port with and without a queue; the deliberate faults caught at the right
# scanline through a four-word port.
foreach(name grey_p2 grey_p4 rgb2_p8 grey_p4_q2 rgb2_p8_q3 grey_p1_q2)
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND rtl_cosim_cpp --config ${name} --scenario all --seed 1 --runs 3
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
endforeach()
foreach(name grey_p4 grey_p4_q2)
  foreach(scenario mixed tiny)
    add_test(NAME rtl_cosim_sc_${name}_${scenario}
      COMMAND rtl_cosim_sc --config ${name} --scenario ${scenario} --seed 7
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endforeach()
endforeach()
add_test(NAME rtl_cosim_catches_lsb_fault_p4
  COMMAND rtl_cosim_cpp --config fault_lsb_p4 --scenario mixed --seed 3 --stall-pct 0
          --expect-mismatch pixel:17 --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
add_test(NAME rtl_cosim_catches_stall_fault_p4
  COMMAND rtl_cosim_cpp --config fault_stall_p4 --scenario mixed --seed 3 --stall-pct 0
          --expect-mismatch cycle:23 --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
add_test(NAME rtl_lint_grey_p4
  COMMAND verilator --lint-only -Wall ${RTL_CONFIG_grey_p4_PARAMS} --top-module shade_unit ${RTL_SOURCES})
add_test(NAME rtl_lint_rgb2_p8
  COMMAND verilator --lint-only -Wall ${RTL_CONFIG_rgb2_p8_PARAMS} --top-module shade_unit ${RTL_SOURCES})
add_test(NAME rtl_lint_rgb2_p8_q3
  COMMAND verilator --lint-only -Wall ${RTL_CONFIG_rgb2_p8_q3_PARAMS} --top-module shade_unit ${RTL_SOURCES})
# The specular-unit configurations: every scenario (non-zero specular colours, unit parameters,
# LUT tables), one seed each in CI; the SystemC backend on one scenario where it is built.
foreach(name ${RTL_SPECULAR_CONFIG_NAMES})
  add_test(NAME rtl_lint_${name}
    COMMAND verilator --lint-only -Wall ${RTL_CONFIG_${name}_PARAMS} --top-module shade_unit ${RTL_SOURCES})
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND rtl_cosim_cpp --config ${name} --scenario all --seed 21 --runs 1 --min-spec-pct 25
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  if("sc" IN_LIST RTL_CONFIG_${name}_BACKENDS)
    add_test(NAME rtl_cosim_sc_${name}_mixed
      COMMAND rtl_cosim_sc --config ${name} --scenario mixed --seed 23 --min-spec-pct 25
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endif()
endforeach()
add_test(NAME rtl_cosim_backends_agree_schlick_iter_d
  COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/same_results.sh ${CMAKE_BINARY_DIR} schlick_iter_d switch 5)
# Both backends give the same pixels, scanlines and cycles on the same run.
add_test(NAME rtl_cosim_backends_agree
  COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/same_results.sh ${CMAKE_BINARY_DIR} rgb2_s320s mixed 11)
# The harness must catch deliberate faults at the right scanline.
add_test(NAME rtl_cosim_catches_lsb_fault
  COMMAND rtl_cosim_cpp --config fault_lsb --scenario mixed --seed 3 --stall-pct 0
          --expect-mismatch pixel:17 --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
add_test(NAME rtl_cosim_catches_stall_fault
  COMMAND rtl_cosim_cpp --config fault_stall --scenario mixed --seed 3 --stall-pct 0
          --expect-mismatch cycle:23 --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
set_tests_properties(rtl_cosim_catches_lsb_fault rtl_cosim_catches_stall_fault PROPERTIES
  LABELS rtl)

# Cycle model on its own, against closed forms.
add_executable(rtl_cycle_model_test ${CMAKE_SOURCE_DIR}/tests/rtl/cycle_model_test.cpp)
target_link_libraries(rtl_cycle_model_test PRIVATE shadesim_harness GTest::gtest_main)
add_test(NAME rtl_cycle_model_test COMMAND rtl_cycle_model_test)

# The executables' machine interface: --json, exit codes, replay, --list --json; --waves.
add_test(NAME rtl_cosim_cli
  COMMAND ${CMAKE_COMMAND} -DMODE=json -DCOSIM=$<TARGET_FILE:rtl_cosim_cpp> -DWORK=${CMAKE_BINARY_DIR}/rtl_cli
          -P ${CMAKE_SOURCE_DIR}/sim/harness/cosim_cli_check.cmake)
add_test(NAME rtl_cosim_waves
  COMMAND ${CMAKE_COMMAND} -DMODE=waves -DCOSIM=$<TARGET_FILE:rtl_cosim_cpp_trace> -DWORK=${CMAKE_BINARY_DIR}/rtl_waves
          -P ${CMAKE_SOURCE_DIR}/sim/harness/cosim_cli_check.cmake)
