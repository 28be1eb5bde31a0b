# Standalone checks of the specular units' RTL (rtl/exponent_lut.sv, schlick_divider.sv,
# wpow_unit.sv, specular_unit.sv) against their model classes.
#
# Every configuration is Verilated once, straight into the one test executable rtl_units_test;
# its parameters are written to a generated header as "NAME=VALUE ..." text, which the test
# parses into the model's LutConfig / SchlickConfig / WpowConfig, so CMake and C++ cannot disagree.
# The unit's own fields are given by slot, SLOTk=V (SPEC_PARAMS slot k, packed here by
# spec_params_literal); the test maps them to fields through the unit's row of
# model/specular_units.cpp, so a slot the RTL decodes differently from the row fails the test.
find_package(verilator 5 HINTS $ENV{VERILATOR_ROOT})
if(NOT verilator_FOUND)
  message(WARNING "Verilator not found: specular-unit RTL tests are skipped")
  return()
endif()
find_program(IVERILOG iverilog)
find_program(YOSYS yosys)
include(${CMAKE_SOURCE_DIR}/cmake/spec_params.cmake)

set(RTL_UNITS_GEN ${CMAKE_BINARY_DIR}/verilated/units)
# The leaves of rtl/files.f up to specular_unit.sv (the units, the slot and what they use).
include(${CMAKE_SOURCE_DIR}/cmake/rtl_files.cmake)
rtl_files(RTL_UNITS_SOURCES UNTIL specular_unit.sv)
# The per-exponent table the "lut_file" configuration loads at time 0 ($readmemh); the test
# writes it with ExponentLut::write_hex before it builds the model, and removes it to check that
# a missing file is fatal.
set(RTL_UNITS_TABLE_FILE ${RTL_UNITS_GEN}/lut_file_table.hex)

add_executable(rtl_units_test
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/lut_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/schlick_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/wpow_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/slot_rtl_test.cpp)
# 125 Verilated objects of small units on short sweeps: -O1 halves their compile, and the sweeps
# still take seconds. Each object is a few lines beside verilated.h, so they are compiled as
# unity files of 16, one parse of the runtime's headers each: 168 -> 34 CPU-s (ninja -j2
# rtl_units_test from no objects, one machine). Every generated name carries its model's prefix,
# so models share a unity file safely; the tests' own files keep their translation units (their
# anonymous namespaces reuse names).
target_compile_options(rtl_units_test PRIVATE $<$<CONFIG:Release>:-O1>)
set_target_properties(rtl_units_test PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 16)
set_source_files_properties(
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/lut_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/schlick_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/wpow_rtl_test.cpp
  ${CMAKE_SOURCE_DIR}/tests/rtl_units/slot_rtl_test.cpp
  PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)

set(RTL_UNITS_ENTRIES "")
set(RTL_UNITS_INCLUDES "")
# rtl_unit(<name> <top module> <NAME=VALUE>...): one Verilated configuration of a unit.
function(rtl_unit name top)
  set(named "")
  set(slots "")
  foreach(p ${ARGN})
    if(p MATCHES "^SLOT([0-9]+)=(.*)$")
      list(LENGTH slots n)
      if(NOT CMAKE_MATCH_1 EQUAL n)
        message(FATAL_ERROR "rtl_unit(${name}): SLOT${CMAKE_MATCH_1} out of order (expected SLOT${n})")
      endif()
      list(APPEND slots ${CMAKE_MATCH_2})
    else()
      list(APPEND named ${p})
    endif()
  endforeach()
  if(slots)
    spec_params_literal(spec ${slots})
    list(APPEND named SPEC_PARAMS=${spec})
  endif()
  set(gparams "")
  foreach(p ${named})
    list(APPEND gparams -G${p})
  endforeach()
  set(extra "")
  # W_m's squarer has a synthesis view (a summed square) and a simulation view (a product):
  # its unit builds simulate the synthesis view, so that every base is checked against the
  # model (rtl/wpow_unit.sv).
  if(top STREQUAL "wpow_unit")
    set(extra "-DSYNTHESIS")
  endif()
  if(name STREQUAL "lut_file")
    set(extra "-GTABLE_FILE=\"${RTL_UNITS_TABLE_FILE}\"")
  endif()
  verilate(rtl_units_test
    SOURCES ${RTL_UNITS_SOURCES}
    TOP_MODULE ${top}
    PREFIX V${name}
    DIRECTORY ${RTL_UNITS_GEN}/${name}
    VERILATOR_ARGS -Wall ${gparams} ${extra} --x-assign unique --x-initial unique)
  string(REPLACE ";" " " text "${ARGN}")
  set(RTL_UNITS_ENTRIES "${RTL_UNITS_ENTRIES}X(${name}, \"${text}\") \\\n" PARENT_SCOPE)
  set(RTL_UNITS_INCLUDES "${RTL_UNITS_INCLUDES}#include \"V${name}.h\"\n" PARENT_SCOPE)
  # Static checks of the same configuration: lint clean, Icarus accepts it.
  add_test(NAME rtl_units_lint_${name}
    COMMAND verilator --lint-only -Wall ${gparams} --top-module ${top} ${RTL_UNITS_SOURCES})
  if(IVERILOG)
    set(pparams "")
    foreach(p ${named})
      list(APPEND pparams -P${top}.${p})
    endforeach()
    add_test(NAME rtl_units_iverilog_${name}
      COMMAND ${IVERILOG} -g2012 -Wall ${pparams} -s ${top}
              -o ${RTL_UNITS_GEN}/${name}.vvp ${RTL_UNITS_SOURCES})
  endif()
endfunction()

# Exponent LUT: smallest widths with exhaustive inputs; interpolation with nearest index and a
# rounded output; the default-sized table loaded from a $readmemh file.
# Slots (the decode at the top of each module): exponent_lut 0 ADDR_BITS, 1 ENTRY_BITS,
# 2 INTERP_BITS, 3 INDEX; schlick_divider 0 QUOTIENT_BITS, 1 OPERAND_BITS, 2 TIMING; wpow_unit
# 0 MAX_M, 1 BASE_BITS, 2 TIMING, 3 SQUARE_STAGES.
rtl_unit(lut_small exponent_lut SLOT0=4 SLOT1=6 SLOT2=0 SLOT3=0
         SERIES_WL=12 SERIES_IWL=3 OUT_WL=9 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(lut_interp exponent_lut SLOT0=5 SLOT1=8 SLOT2=3 SLOT3=1
         SERIES_WL=14 SERIES_IWL=3 OUT_WL=7 OUT_IWL=1 OUT_QUANT=1 OUT_OVERFLOW=0)
rtl_unit(lut_file exponent_lut SLOT0=10 SLOT1=8 SLOT2=0 SLOT3=0
         SERIES_WL=32 SERIES_IWL=4 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
# Schlick divider: smallest widths (exhaustive operand pairs, output wider than the quotient)
# both timings; the default widths iterative; a long pipeline with a rounded narrow output.
rtl_unit(schlick_small_pipe schlick_divider SLOT0=3 SLOT1=2 SLOT2=0
         SERIES_WL=7 SERIES_IWL=2 OUT_WL=5 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(schlick_small_iter schlick_divider SLOT0=3 SLOT1=2 SLOT2=1
         SERIES_WL=7 SERIES_IWL=2 OUT_WL=5 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(schlick_iter schlick_divider SLOT0=16 SLOT1=24 SLOT2=1
         SERIES_WL=32 SERIES_IWL=4 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(schlick_pipe schlick_divider SLOT0=20 SLOT1=12 SLOT2=0
         SERIES_WL=23 SERIES_IWL=3 OUT_WL=13 OUT_IWL=1 OUT_QUANT=1 OUT_OVERFLOW=0)
# W_m: m = 4 with 4-bit base both timings (exhaustive), m = 1 (no squarer), m = 2 with a 16-bit
# base (every square of the squarer), W16 default
# pipelined, m = 32 iterative with a rounded output.
rtl_unit(wpow_small_pipe wpow_unit SLOT0=4 SLOT1=4 SLOT2=0 SLOT3=1
         SERIES_WL=8 SERIES_IWL=2 OUT_WL=6 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_small_iter wpow_unit SLOT0=4 SLOT1=4 SLOT2=1 SLOT3=1
         SERIES_WL=8 SERIES_IWL=2 OUT_WL=6 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_m1 wpow_unit SLOT0=1 SLOT1=2 SLOT2=1 SLOT3=1
         SERIES_WL=8 SERIES_IWL=2 OUT_WL=4 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_m2_b16 wpow_unit SLOT0=2 SLOT1=16 SLOT2=0 SLOT3=1
         SERIES_WL=18 SERIES_IWL=2 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_w16 wpow_unit SLOT0=16 SLOT1=16 SLOT2=0 SLOT3=1
         SERIES_WL=32 SERIES_IWL=4 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_m32_iter wpow_unit SLOT0=32 SLOT1=12 SLOT2=1 SLOT3=1
         SERIES_WL=23 SERIES_IWL=3 OUT_WL=9 OUT_IWL=1 OUT_QUANT=1 OUT_OVERFLOW=0)
# Split squarings (SLOT3 = square_stages 2): m = 4 with an odd and an even 1.B base
# (exhaustive), m = 2 with a 16-bit base (every square), W16 at the real widths.
rtl_unit(wpow_small_sq2 wpow_unit SLOT0=4 SLOT1=4 SLOT2=0 SLOT3=2
         SERIES_WL=8 SERIES_IWL=2 OUT_WL=6 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_small_b5_sq2 wpow_unit SLOT0=4 SLOT1=5 SLOT2=0 SLOT3=2
         SERIES_WL=9 SERIES_IWL=2 OUT_WL=6 OUT_IWL=1 OUT_QUANT=1 OUT_OVERFLOW=0)
rtl_unit(wpow_m2_b16_sq2 wpow_unit SLOT0=2 SLOT1=16 SLOT2=0 SLOT3=2
         SERIES_WL=18 SERIES_IWL=2 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
rtl_unit(wpow_w16_sq2 wpow_unit SLOT0=16 SLOT1=16 SLOT2=0 SLOT3=2
         SERIES_WL=32 SERIES_IWL=4 OUT_WL=17 OUT_IWL=1 OUT_QUANT=0 OUT_OVERFLOW=0)
# The slot: the cfg-port mapping and the timing contract through the wrapper.
rtl_unit(slot_lut specular_unit SPECULAR_KIND=1 SERIES_WL=16 SERIES_IWL=3 SERIES_PER_LIGHT=1
         SPECULAR_OUT_WL=12 SPECULAR_OUT_IWL=1 SLOT0=6 SLOT1=10 SLOT2=2 SLOT3=1)
rtl_unit(slot_schlick specular_unit SPECULAR_KIND=2 SERIES_WL=32 SERIES_IWL=4 SERIES_PER_LIGHT=2
         SPECULAR_OUT_WL=17 SPECULAR_OUT_IWL=1 SLOT0=12 SLOT1=16 SLOT2=1)
rtl_unit(slot_wpow specular_unit SPECULAR_KIND=3 SERIES_WL=20 SERIES_IWL=4 SERIES_PER_LIGHT=1
         SPECULAR_OUT_WL=11 SPECULAR_OUT_IWL=1 SLOT0=8 SLOT1=10 SLOT2=1 SLOT3=1)
rtl_unit(slot_ideal specular_unit SPECULAR_KIND=0 SERIES_WL=32 SERIES_IWL=4 SERIES_PER_LIGHT=1
         SPECULAR_OUT_WL=17 SPECULAR_OUT_IWL=1)

file(WRITE ${RTL_UNITS_GEN}/rtl_units_configs.inc.new
     "// Generated by cmake/rtl_units.cmake: the unit configurations Verilated into rtl_units_test.\n${RTL_UNITS_INCLUDES}#define SHADESIM_RTL_UNIT_CONFIGS(X) \\\n${RTL_UNITS_ENTRIES}\n")
configure_file(${RTL_UNITS_GEN}/rtl_units_configs.inc.new ${RTL_UNITS_GEN}/rtl_units_configs.inc COPYONLY)
target_include_directories(rtl_units_test PRIVATE ${CMAKE_SOURCE_DIR} ${RTL_UNITS_GEN})
target_compile_definitions(rtl_units_test PRIVATE
  SHADESIM_RTL_UNITS_TABLE_FILE="${RTL_UNITS_TABLE_FILE}")
target_link_libraries(rtl_units_test PRIVATE shadesim_model GTest::gtest_main)
add_test(NAME rtl_units_test COMMAND rtl_units_test)
set_tests_properties(rtl_units_test PROPERTIES TIMEOUT 300)

# Yosys: each unit synthesizes without latches (small widths: this is about structure).
if(YOSYS)
  # SPEC_PARAMS by slot, as above: lut A 6, B 8, F 3, truncate; schlick Q 10, D 12; W_m m 16, B 10.
  spec_params_literal(lut 6 8 3 0)
  spec_params_literal(schlick_iter 10 12 1)
  spec_params_literal(schlick_pipe 10 12 0)
  spec_params_literal(wpow_pipe 16 10 0)
  spec_params_literal(wpow_iter 16 10 1)
  foreach(cfg
      "lut:-set SPECULAR_KIND 1 -set SPEC_PARAMS ${lut}"
      "schlick_iter:-set SPECULAR_KIND 2 -set SERIES_PER_LIGHT 2 -set SPEC_PARAMS ${schlick_iter}"
      "schlick_pipe:-set SPECULAR_KIND 2 -set SERIES_PER_LIGHT 2 -set SPEC_PARAMS ${schlick_pipe}"
      "wpow_pipe:-set SPECULAR_KIND 3 -set SPEC_PARAMS ${wpow_pipe}"
      "wpow_iter:-set SPECULAR_KIND 3 -set SPEC_PARAMS ${wpow_iter}")
    string(REGEX REPLACE ":.*" "" cname "${cfg}")
    string(REGEX REPLACE "^[^:]*:" "" cparams "${cfg}")
    add_test(NAME rtl_units_yosys_${cname}
      COMMAND ${CMAKE_SOURCE_DIR}/tests/rtl_units/yosys_unit_check.sh ${YOSYS}
              ${RTL_UNITS_GEN}/yosys_${cname}.log "${cparams}" ${RTL_UNITS_SOURCES})
  endforeach()
endif()
