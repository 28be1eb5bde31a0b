# Formal checks of shade_unit (docs/formal.md): tests/formal/shade_formal.sv's properties on
# small configurations, through Yosys and ABC (yosys-abc, shipped with Yosys). Each test labelled
# `formal` besides its tier (cmake/test_tiers.cmake: rtl_formal_* are rtl).
#
#   rtl_formal_<config>          handshake and queue properties, proven for all time (pdr)
#   rtl_formal_conservation_*    the span scoreboard and END_FRAME drain, BMC to a stated depth
#   rtl_formal_broken_<bug>      a deliberately broken RTL copy: the check must fail, with a VCD
find_program(YOSYS_ABC yosys-abc)
find_package(Python3 COMPONENTS Interpreter QUIET)
if(NOT YOSYS OR NOT YOSYS_ABC OR NOT Python3_FOUND)
  # cmake/required_tools.cmake already refused a missing Yosys unless opted out.
  shadesim_left_out(formal "formal checks: yosys, yosys-abc or python3 missing")
  return()
endif()

set(_formal_dir ${CMAKE_SOURCE_DIR}/tests/formal)
set(_formal_work ${CMAKE_BINARY_DIR}/formal)
function(_formal_test name)
  add_test(NAME rtl_formal_${name} COMMAND ${ARGN})
  # 2 to 55 s each: their COST (cmake/test_costs.cmake) starts them among the first tests.
  set_tests_properties(rtl_formal_${name} PROPERTIES LABELS formal)
endfunction()

# One configuration per specular kind: lanes 1 and 2, queue 1 and 2, material buffers 1 and 2.
foreach(config ideal_l1_q1 lut_l2_q2 schlick_l1_q1 wpow_l2_q1_mb2 none_l2_q1)
  _formal_test(${config} ${Python3_EXECUTABLE} ${_formal_dir}/run.py ${config} --mode prove
               --work ${_formal_work}/${config})
endforeach()
# The span scoreboard and END_FRAME: BMC, 12 cycles from reset (two whole spans and a drained
# END_FRAME fit in it: docs/formal.md), on one lane without a queue and two lanes with one.
foreach(config ideal_l1_q1 lut_l2_q2)
  _formal_test(conservation_${config} ${Python3_EXECUTABLE} ${_formal_dir}/run.py ${config}
               --mode bmc --depth 12 --check conservation --work ${_formal_work}/cons_${config})
endforeach()
foreach(bug queue_off_by_one pix_handshake pix_valid_drop)
  _formal_test(broken_${bug} ${_formal_dir}/broken.sh ${bug} ${_formal_work}/broken_${bug})
endforeach()
# The command decoder (+ payload FSM, + start bank with host setup) against its pre-issue-44
# copies in tests/data/decoder_ref/ (tests/formal/equiv_decoder.py, docs/rtl.md "The command
# decoder's structure"): the outputs equal every cycle from reset for every input, proven by pdr.
# CI proves sphere's and specular's own units and one- to eight-word ports with unit setup, queue,
# two material buffers and host setup (about 2 min); -DSHADESIM_FORMAL_ALL=ON adds torus's and
# multi's own units and the eight-word port with host setup (about 2 more). p8_host (7 minutes) and
# suzanne (specular's structure) are left to a run by hand. Last, a copy broken by one character,
# which the check must catch.
option(SHADESIM_FORMAL_ALL "Prove the decoder equivalence on every listed configuration" OFF)
set(_decoder_configs sphere specular p1_unit p1_host p2_queued_mb2 p4_unit_mb2 p4_queued
                     p8_queued_mb2)
if(SHADESIM_FORMAL_ALL)
  list(APPEND _decoder_configs torus multi p8_host_short)
endif()
foreach(config ${_decoder_configs})
  _formal_test(equiv_decoder_${config} ${Python3_EXECUTABLE} ${_formal_dir}/equiv_decoder.py
               ${config} --work ${_formal_work}/equiv_decoder_${config})
endforeach()
_formal_test(equiv_decoder_catches_broken ${Python3_EXECUTABLE} ${_formal_dir}/equiv_decoder.py
             sphere --expect-fail --work ${_formal_work}/equiv_decoder_broken
             "--break=cmd_payload.sv:pay_rem_q < 16'(2 * PORT:pay_rem_q <= 16'(2 * PORT")
