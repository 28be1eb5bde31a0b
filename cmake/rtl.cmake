# RTL (rtl/*.sv) checks and co-simulation tests.
#
# The RTL builds themselves are not CMake targets: shadesim Verilates each unit configuration on
# demand into <build>/rtl-cache (sim/eda/verilator/rtl_build.h), with its Verilog parameters from the one
# mapping in model/rtl_parameters.cpp. The named builds the tests share are listed in
# sim/harness/builds.json; the `rtl_builds` target below builds them (and the traced builds the
# waveform tests use) once, in parallel, so every test finds them in the cache.
find_package(verilator 5 HINTS $ENV{VERILATOR_ROOT})
if(NOT verilator_FOUND)
  message(WARNING "Verilator not found: RTL co-simulation targets and tests are skipped")
  return()
endif()
find_program(VERILATOR_BIN verilator REQUIRED)
find_program(IVERILOG iverilog)
find_program(YOSYS yosys)
set(SHADESIM_HAVE_RTL ON)

set(RTL_DIR ${CMAKE_SOURCE_DIR}/rtl)
# Dependency order (leaves first), from the one list rtl/files.f every tool reads.
include(${CMAKE_SOURCE_DIR}/cmake/rtl_files.cmake)
rtl_files(RTL_SOURCES)
# The harness's deliberate-fault hooks (test apparatus, outside rtl/): a simulation of a build
# with fault hooks compiles them after the RTL (Verilator adds sim/harness/faults/fault_bind.sv;
# the Icarus testbench instantiates them); synthesis never reads them.
rtl_files(FAULT_HOOK_SOURCES DIR ${CMAKE_SOURCE_DIR}/sim/harness/faults)
set(RTL_SIM_SOURCES ${RTL_SOURCES} ${FAULT_HOOK_SOURCES})

# The named builds (and what the tests iterate over), read from the same file shadesim reads.
file(READ ${CMAKE_SOURCE_DIR}/sim/harness/builds.json _builds_json)
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/sim/harness/builds.json)
string(JSON _n LENGTH "${_builds_json}")
math(EXPR _last "${_n} - 1")
set(RTL_BUILD_NAMES "")
set(RTL_SPECULAR_BUILD_NAMES "")
set(RTL_NO_SPECULAR_BUILD_NAMES "")  # specular kind none: no unit, no specular series
foreach(i RANGE ${_last})
  string(JSON name MEMBER "${_builds_json}" ${i})
  if(name MATCHES "^_")
    continue()
  endif()
  list(APPEND RTL_BUILD_NAMES ${name})
  string(JSON kind ERROR_VARIABLE no_kind GET "${_builds_json}" ${name} unit specular kind)
  string(JSON _nb LENGTH "${_builds_json}" ${name} backends)
  set(RTL_BUILD_${name}_BACKENDS "")
  math(EXPR _nb_last "${_nb} - 1")
  foreach(k RANGE ${_nb_last})
    string(JSON b GET "${_builds_json}" ${name} backends ${k})
    list(APPEND RTL_BUILD_${name}_BACKENDS ${b})
  endforeach()
  if(NOT no_kind AND NOT kind STREQUAL "ideal" AND NOT kind STREQUAL "none")
    list(APPEND RTL_SPECULAR_BUILD_NAMES ${name})
  elseif(NOT no_kind AND kind STREQUAL "none")
    list(APPEND RTL_NO_SPECULAR_BUILD_NAMES ${name})
  endif()
endforeach()

set(SHADESIM_CLI $<TARGET_FILE:shadesim>)
set(RTL_CACHE ${CMAKE_BINARY_DIR}/rtl-cache)
# Every named build on its own backends, plus the traced builds of the waveform tests. Always
# run: a build whose inputs have not changed is a cache hit (hashing the inputs takes < 1 s).
# Quick (-O0): the tests' runs are short (cosim picks quick for its random scenarios, regress by
# each run's length), and a quick build compiles in about a third of a fast one's time.
# The named builds regress_shipped_scenes_named_builds runs every shipped scene on (1.4 M
# cycles and more each, so regress wants them fast) are made fast first. A fast build leaves the
# SVA out (checks_assertions, sim/eda/verilator/rtl_recipe.h), so the quick runs on them have builds of
# their own. The fault-hook variants are what the rtl_cosim_catches_fault_* tests run (and the
# waveform test's failing run); every other run uses each build without its hooks.
set(RTL_SHIPPED_SCENE_BUILDS lut_d schlick_iter_d schlick_pipe_d wpow16_d lut_n schlick_iter_n
    schlick_pipe_n wpow16_n)
add_custom_target(rtl_builds ALL
  COMMAND shadesim rtl-build --config ${RTL_SHIPPED_SCENE_BUILDS} --backends cpp --opt fast
          --cache ${RTL_CACHE}
  COMMAND shadesim rtl-build --runtime --all --opt quick --cache ${RTL_CACHE}
  COMMAND shadesim rtl-build --all --fault-hooks --backends cpp --opt quick --cache ${RTL_CACHE}
  COMMAND shadesim rtl-build --config grey_s428w --backends cpp_trace --opt quick --cache ${RTL_CACHE}
  COMMAND shadesim rtl-build --config grey_s428w --fault-hooks --backends cpp_trace --opt quick
          --cache ${RTL_CACHE}
  DEPENDS shadesim shadesim_harness shadesim_model
  COMMENT "Verilating the named RTL builds into ${RTL_CACHE} (cache hits are instant)"
  USES_TERMINAL)

# `shadesim cosim --backend B --config NAME ...` as a test command.
macro(_cosim out backend)
  set(${out} ${SHADESIM_CLI} cosim --backend ${backend} --cache ${RTL_CACHE})
endmacro()
_cosim(COSIM_CPP cpp)
_cosim(COSIM_SC systemc)

# ---- tests --------------------------------------------------------------------------------------
# Static checks on the RTL: lint (every named build's parameters), Icarus, Yosys (no latches).
foreach(name ${RTL_BUILD_NAMES})
  add_test(NAME rtl_lint_${name}
    COMMAND sh -c "exec ${VERILATOR_BIN} --lint-only -Wall $(\"$0\" rtl-params --config ${name}) --top-module shade_unit \"$@\""
            ${SHADESIM_CLI} ${RTL_SOURCES})
endforeach()
# The fault hooks bound into a four-lane RGB unit, as a build with fault hooks Verilates them
# (-fno-dfg: sim/eda/verilator/rtl_recipe.cpp says why).
add_test(NAME rtl_lint_fault_hooks
  COMMAND ${VERILATOR_BIN} --lint-only -Wall -fno-dfg -GLANES=4 -GCHANNELS=3 -GLIGHTS=2
          --top-module shade_unit ${RTL_SIM_SOURCES} ${CMAKE_SOURCE_DIR}/sim/harness/faults/fault_bind.sv)
if(IVERILOG)
  add_test(NAME rtl_iverilog
    COMMAND ${IVERILOG} -g2012 -Wall -s shade_unit -o ${CMAKE_BINARY_DIR}/rtl_iverilog.vvp ${RTL_SOURCES})
endif()
if(YOSYS)
  include(${CMAKE_SOURCE_DIR}/cmake/spec_params.cmake)
  # SPEC_PARAMS by slot (the decode at the top of each unit's module): W_m m 4, B 8, timing;
  # the LUT A 4, B 8, F 2, truncate.
  spec_params_literal(_yosys_wpow0 4 8 0)
  spec_params_literal(_yosys_wpow1 4 8 1)
  spec_params_literal(_yosys_lut 4 8 2 0)
  # The variants stop after `proc`, where latches are inferred (sim/harness/yosys_check.sh);
  # rtl_yosys_no_latch synthesises the default unit in full, the area tests others.
  set(_latch_passes "YOSYS_LATCH_ONLY=1")
  add_test(NAME rtl_yosys_no_latch
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys.log ${RTL_SOURCES})
  # shade_unit's slot glue: the metadata delay line (pipelined W_m, latency 3) and the pending
  # register of an iterative unit (W_m iterative); small units keep synthesis quick.
  foreach(timing 0 1)
    add_test(NAME rtl_yosys_no_latch_wpow_timing${timing}
      COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_wpow${timing}.log ${RTL_SOURCES})
    set_tests_properties(rtl_yosys_no_latch_wpow_timing${timing} PROPERTIES
      ENVIRONMENT "${_latch_passes};YOSYS_CHPARAM=-set SPECULAR_KIND 3 -set SPEC_PARAMS ${_yosys_wpow${timing}}")
  endforeach()
  # The wide port's beat decoder and the triangle queue's banks and span queue.
  add_test(NAME rtl_yosys_no_latch_port4_queue3
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_p4q3.log ${RTL_SOURCES})
  set_tests_properties(rtl_yosys_no_latch_port4_queue3 PROPERTIES
    ENVIRONMENT "${_latch_passes};YOSYS_CHPARAM=-set PORT_WORDS 4 -set TRI_QUEUE 3")
  # Two material buffers: the banked material registers and each unit's banked parameters with
  # the bank tag in its stages (LUT; W_m pipelined and iterative), behind a triangle queue.
  set(_yosys_m2_lut "-set SPECULAR_KIND 1 -set SPEC_PARAMS ${_yosys_lut}")
  set(_yosys_m2_wpow0 "-set SPECULAR_KIND 3 -set SPEC_PARAMS ${_yosys_wpow0}")
  set(_yosys_m2_wpow1 "-set SPECULAR_KIND 3 -set SPEC_PARAMS ${_yosys_wpow1}")
  foreach(unit lut wpow0 wpow1)
    add_test(NAME rtl_yosys_no_latch_material_buffers2_${unit}
      COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_m2_${unit}.log ${RTL_SOURCES})
    set_tests_properties(rtl_yosys_no_latch_material_buffers2_${unit} PROPERTIES
      ENVIRONMENT "${_latch_passes};YOSYS_CHPARAM=-set MATERIAL_BUFFERS 2 -set TRI_QUEUE 2 ${_yosys_m2_${unit}}")
  endforeach()
  # Four pixel lanes: each lane's fan-out, engines and combine, the wider metadata line.
  add_test(NAME rtl_yosys_no_latch_lanes4
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_l4.log ${RTL_SOURCES})
  set_tests_properties(rtl_yosys_no_latch_lanes4 PROPERTIES
    ENVIRONMENT "${_latch_passes};YOSYS_CHPARAM=-set LANES 4 -set SPECULAR_KIND 3 -set SPEC_PARAMS ${_yosys_wpow1}")
  # Host span setup: the start bank (two entries) behind a four-word port, two lanes.
  add_test(NAME rtl_yosys_no_latch_host_setup
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_check.sh ${YOSYS} ${CMAKE_BINARY_DIR}/rtl_yosys_host.log ${RTL_SOURCES})
  set_tests_properties(rtl_yosys_no_latch_host_setup PROPERTIES
    ENVIRONMENT "${_latch_passes};YOSYS_CHPARAM=-set SPAN_SETUP 1 -set START_DEPTH 2 -set PORT_WORDS 4 -set LANES 2 -set MATERIAL_BUFFERS 2")
  # The flat netlist behaves like the RTL: every bit of pix_colour_o, pix_x_o and pix_y_o is its
  # own flip-flop (no constant or aliased lanes). A small four-lane unit with a pipelined slot
  # (LUT A 4, B 4: the metadata delay line) behind a four-word port and a triangle queue (the
  # span queue), about 15-20 s of Yosys. Yosys 0.23 once misread both: the line's packed array
  # of structs (lanes 1..3 merged, x and y constant 0) and the span queue's unpacked array of
  # span_t (y constant 0).
  spec_params_literal(_yosys_lut_small 4 4 0 0)
  add_test(NAME rtl_yosys_flat_outputs_lanes4
    COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_outputs_check.py ${YOSYS}
            ${CMAKE_BINARY_DIR}/rtl_yosys_flat_l4 ${RTL_SOURCES})
  # The checker itself, on two netlists (sim/harness/yosys_outputs_fixtures): a correct one
  # passes, the pre-fix four-lane netlist's outputs fail.
  foreach(f good bad)
    add_test(NAME rtl_yosys_flat_outputs_self_test_${f}
      COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/yosys_outputs_check.py -
              ${CMAKE_SOURCE_DIR}/sim/harness/yosys_outputs_fixtures/${f})
  endforeach()
  set_tests_properties(rtl_yosys_flat_outputs_self_test_bad PROPERTIES PASS_REGULAR_EXPRESSION
    "assign pix_x_o = 4'h0;.*pix_colour_o: 8 of 16 bits are their own flip-flop")
  set_tests_properties(rtl_yosys_flat_outputs_lanes4 PROPERTIES
    ENVIRONMENT "YOSYS_CHPARAM=-set XY_BITS 4 -set COEF_WL 8 -set COEF_IWL 2 -set SERIES_WL 6 -set SERIES_IWL 2 -set OUT_BITS 3 -set SPEC_COLOUR_WL 4 -set SPECULAR_OUT_WL 5 -set SPECULAR_OUT_IWL 1 -set LANES 4 -set PORT_WORDS 4 -set TRI_QUEUE 2 -set SPECULAR_KIND 1 -set SPEC_PARAMS ${_yosys_lut_small}")
endif()

# Co-simulation: every scenario (--scenario all includes "edge"), several seeds, both backends,
# both width sets.
foreach(name grey_s428w rgb2_s320s)
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND ${COSIM_CPP} --config ${name} --scenario all --seed 1 --runs 3
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  foreach(scenario mixed long short slow maxbp switch tiny edge)
    add_test(NAME rtl_cosim_sc_${name}_${scenario}
      COMMAND ${COSIM_SC} --config ${name} --scenario ${scenario} --seed 7
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endforeach()
endforeach()
# Wider command ports and triangle queues: every scenario, three seeds; SystemC on
# the four-word port (its sc_bv command port; queues run under SystemC in grey_p4_q2_l4_m2 below
# and wpow16_d_p8_q2_l4_m2 with the specular builds); the deliberate faults caught at the right
# scanline through a four-word port. _pack: packed coefficients (rgb2_pack_p8_q3, a LUT build,
# runs with the specular builds below). grey_p2 narrows term T4 by one integer bit: every term
# still takes a word of its own, so coef_bank loads each from its own width (g_coef_packed).
# grey_p1_host_d1: host span setup with a one-entry start bank (start_depth 1).
foreach(name grey_p2 grey_p4 rgb2_p8 grey_p4_q2 rgb2_p8_q3 grey_p1_q2 grey_pack_p4_q2
        grey_p1_host_d1)
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND ${COSIM_CPP} --config ${name} --scenario all --seed 1 --runs 3
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
endforeach()
foreach(name grey_p4)
  foreach(scenario mixed tiny)
    add_test(NAME rtl_cosim_sc_${name}_${scenario}
      COMMAND ${COSIM_SC} --config ${name} --scenario ${scenario} --seed 7
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endforeach()
endforeach()
# Pixel lanes: every scenario, three seeds, on wrapping and saturating series; the
# SystemC backend on four lanes; the deliberate faults caught at the right scanline through a
# four-word port with four lanes. The specular-unit lane builds run with the others below.
foreach(name grey_p4_q2_l2 grey_p4_q2_l4_m2 rgb2_p8_q3_l4)
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND ${COSIM_CPP} --config ${name} --scenario all --seed 1 --runs 3
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
endforeach()
foreach(scenario mixed tiny long)
  add_test(NAME rtl_cosim_sc_grey_p4_q2_l4_m2_${scenario}
    COMMAND ${COSIM_SC} --config grey_p4_q2_l4_m2 --scenario ${scenario} --seed 7
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
endforeach()
# The specular-unit builds: every scenario (non-zero specular colours, unit parameters, LUT
# tables), one seed each in CI; the SystemC backend on one scenario where it is built.
foreach(name ${RTL_SPECULAR_BUILD_NAMES})
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND ${COSIM_CPP} --config ${name} --scenario all --seed 21 --runs 1 --min-spec-pct 25
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  if("systemc" IN_LIST RTL_BUILD_${name}_BACKENDS)
    add_test(NAME rtl_cosim_sc_${name}_mixed
      COMMAND ${COSIM_SC} --config ${name} --scenario mixed --seed 23 --min-spec-pct 25
              --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  endif()
endforeach()
# Specular kind none (no specular unit, no specular series, no specular term in pixel_combine):
# every scenario, one seed; the random streams' specular colours and gate-only masks must add
# nothing in the RTL, as in the model.
foreach(name ${RTL_NO_SPECULAR_BUILD_NAMES})
  add_test(NAME rtl_cosim_cpp_${name}
    COMMAND ${COSIM_CPP} --config ${name} --scenario all --seed 21 --runs 1
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
endforeach()
add_test(NAME rtl_cosim_backends_agree_schlick_iter_n
  COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/same_results.sh ${SHADESIM_CLI} ${RTL_CACHE} schlick_iter_n switch 5)
# Both backends give the same pixels, scanlines and cycles on the same run.
add_test(NAME rtl_cosim_backends_agree
  COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/same_results.sh ${SHADESIM_CLI} ${RTL_CACHE} rgb2_s320s mixed 11)
# The harness must catch each deliberate fault at the right place: its first mismatch of the
# right kind on the fault's row, and for the faults that change every pixel of the row (lsb,
# ch2, x, y, eor) on the row's first pixel, the x0 of the stream's first span on it (":first").
# The others change only some pixels (setup and round where the output rounds differently, spec
# where the highlight shows), or delay a span (stall): only their row is asserted. One build per kind of datapath carries the fault hooks
# (builds.json "fault_hooks"), and each test picks its fault at run time (--fault SITE@Y,
# sim/harness/fault_site.h), under the scenario's own gaps and back-pressure unless noted.
#   NAME  BUILD  SCENARIO  SEED  FAULT  EXPECTED
set(_fault_tests
  # the output of every lane, through one-word and four-word ports
  lsb             grey_s428w        mixed 3  lsb@17    pixel:17:first
  lsb_p4          grey_p4           mixed 3  lsb@17    pixel:17:first
  lsb_p4_l4       grey_p4_q2_l4_m2  mixed 3  lsb@17    pixel:17:first
  # one extra engine stall: a late pixel (back-pressure hides it on some seeds, so 0 here)
  stall           grey_s428w        mixed 3  stall@23  cycle:23
  stall_p4        grey_p4           mixed 3  stall@23  cycle:23
  stall_p4_l4     grey_p4_q2_l4_m2  mixed 3  stall@23  cycle:23
  # engines that stop: the watchdog, not the overall cycle bound, reports a hang on that row
  hang            grey_s428w        short 3  hang@100  hang:100
  # channel 2, position, end of row, span setup and output rounding (RGB, two lights)
  channel2        rgb2_s320s        mixed 5  ch2@19    pixel:19:first
  x               rgb2_s320s        mixed 5  x@21      pixel:21:first
  y               rgb2_s320s        mixed 5  y@22      pixel:22:first
  eor             rgb2_s320s        mixed 5  eor@24    pixel:24:first
  span_setup      rgb2_s320s        mixed 5  setup@26  pixel:26
  rounding        rgb2_s320s        mixed 5  round@27  pixel:27
  # each specular unit's result (LUT, iterative Schlick, iterative W_16)
  spec_lut        lut_n             mixed 5  spec@18   pixel:18
  spec_schlick    schlick_iter_n    mixed 5  spec@18   pixel:18
  spec_wpow       wpow16_n          mixed 5  spec@18   pixel:18
  # host span setup: a start value from the start bank, and a stall behind it
  start_host      lut_n_p4_host_l2_m2 mixed 5 setup@26 pixel:26
  stall_host      lut_n_p4_host_l2_m2 mixed 3 stall@23 cycle:23)
list(LENGTH _fault_tests _n)
math(EXPR _last "${_n} / 6 - 1")
foreach(i RANGE ${_last})
  math(EXPR _at "${i} * 6")
  list(SUBLIST _fault_tests ${_at} 6 _t)
  list(GET _t 0 _name)
  list(GET _t 1 _build)
  list(GET _t 2 _scenario)
  list(GET _t 3 _seed)
  list(GET _t 4 _fault)
  list(GET _t 5 _expect)
  set(_stall)
  if(_fault MATCHES "^stall@")
    set(_stall --stall-pct 0)
  endif()
  add_test(NAME rtl_cosim_catches_fault_${_name}
    COMMAND ${COSIM_CPP} --config ${_build} --scenario ${_scenario} --seed ${_seed} ${_stall}
            --fault ${_fault} --expect-mismatch ${_expect}
            --save-dir ${CMAKE_BINARY_DIR}/rtl_failures)
  set_tests_properties(rtl_cosim_catches_fault_${_name} PROPERTIES LABELS rtl)
endforeach()

# The scoreboard's lane checks (a beat the model did not expect is a mismatch).
add_executable(rtl_scoreboard_lanes_test ${CMAKE_SOURCE_DIR}/tests/rtl/scoreboard_lanes_test.cpp)
shadesim_compile_lighter(rtl_scoreboard_lanes_test)
target_link_libraries(rtl_scoreboard_lanes_test PRIVATE shadesim_harness GTest::gtest_main)
add_test(NAME rtl_scoreboard_lanes_test COMMAND rtl_scoreboard_lanes_test)

# The co-simulation's machine interface: --json, exit codes, replay, --list --json; --waves.
add_test(NAME rtl_cosim_cli
  COMMAND ${CMAKE_COMMAND} -DMODE=json -DSHADESIM=${SHADESIM_CLI} -DCACHE=${RTL_CACHE}
          -DWORK=${CMAKE_BINARY_DIR}/rtl_cli -P ${CMAKE_SOURCE_DIR}/sim/harness/cosim_cli_check.cmake)
add_test(NAME rtl_cosim_waves
  COMMAND ${CMAKE_COMMAND} -DMODE=waves -DSHADESIM=${SHADESIM_CLI} -DCACHE=${RTL_CACHE}
          -DWORK=${CMAKE_BINARY_DIR}/rtl_waves -P ${CMAKE_SOURCE_DIR}/sim/harness/cosim_cli_check.cmake)
# On-demand builds: the cache rebuilds when a parameter or an RTL source changes, reuses the
# build otherwise, and two concurrent builds of one key both succeed.
add_test(NAME rtl_build_cache
  COMMAND ${CMAKE_SOURCE_DIR}/sim/harness/build_cache_check.sh ${SHADESIM_CLI} ${CMAKE_BINARY_DIR}/rtl_cache_check)
set_tests_properties(rtl_build_cache PROPERTIES TIMEOUT 1200)

# A named build's SystemC executable is made by every `cmake --build` (rtl_builds): one that no
# rtl_cosim_sc_<build>_* test runs is build time for nothing, and easily left so when a build's
# tests change. Refused here, naming the build.
get_property(_rtl_tests DIRECTORY PROPERTY TESTS)
foreach(name ${RTL_BUILD_NAMES})
  if("systemc" IN_LIST RTL_BUILD_${name}_BACKENDS)
    set(_sc_run OFF)
    foreach(t ${_rtl_tests})
      if(t MATCHES "^rtl_cosim_sc_${name}_")
        set(_sc_run ON)
        break()
      endif()
    endforeach()
    if(NOT _sc_run)
      message(FATAL_ERROR "sim/harness/builds.json: ${name} lists the systemc backend, but no "
                          "rtl_cosim_sc_${name}_* test runs it (cmake/rtl.cmake): add one or drop "
                          "the backend")
    endif()
  endif()
endforeach()
