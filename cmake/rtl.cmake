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
  ${RTL_DIR}/fixed_round.sv ${RTL_DIR}/fixed_sat.sv ${RTL_DIR}/span_setup.sv
  ${RTL_DIR}/series_engine.sv ${RTL_DIR}/pixel_combine.sv ${RTL_DIR}/specular_slot.sv
  ${RTL_DIR}/shade_unit.sv)

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

# One configuration: the UnitConfig fields as text (the harness parses the same strings into a
# UnitConfig, so CMake and C++ cannot disagree), plus the deliberate-fault rows (-1 = none).
set(RTL_CONFIG_NAMES "")
function(rtl_config name)
  cmake_parse_arguments(C "" "CHANNELS;LIGHTS;XY_BITS;COEF;SERIES;SPEC_COLOUR;OUT_BITS;SPECULAR;SPECULAR_OUT;FAULT_LSB_ROW;FAULT_STALL_ROW" "BACKENDS" ${ARGN})
  foreach(field FAULT_LSB_ROW FAULT_STALL_ROW)
    if(NOT DEFINED C_${field})
      set(C_${field} -1)
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
      ${spec_out} -GFAULT_LSB_ROW=${C_FAULT_LSB_ROW} -GFAULT_STALL_ROW=${C_FAULT_STALL_ROW})
  set(RTL_CONFIG_${name}_PARAMS ${params} PARENT_SCOPE)
  set(RTL_CONFIG_${name}_BACKENDS ${C_BACKENDS} PARENT_SCOPE)
  set(RTL_CONFIG_${name}_ENTRY
      "X(${name}, ${C_CHANNELS}, ${C_LIGHTS}, ${C_XY_BITS}, \"${C_COEF}\", \"${C_SERIES}\", \"${C_SPEC_COLOUR}\", ${C_OUT_BITS}, \"${C_SPECULAR}\", \"${C_SPECULAR_OUT}\", ${C_FAULT_LSB_ROW}, ${C_FAULT_STALL_ROW})"
      PARENT_SCOPE)
  set(RTL_CONFIG_NAMES ${RTL_CONFIG_NAMES} ${name} PARENT_SCOPE)
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
  foreach(name ${RTL_CONFIG_NAMES})
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
    string(APPEND entries "${RTL_CONFIG_${name}_ENTRY}\n")
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
