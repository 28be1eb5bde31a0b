# spec_params_literal(<out> <slot0> <slot1> ...): the SPEC_PARAMS value (rtl/shade_pkg.sv) of a
# specular unit's fields given in slot order, as the sized hex literal Verilator -G, Icarus -P
# and Yosys chparam -set accept ("256'h...", slot k in bits [32k +: 32]; unlisted slots 0).
# model/rtl_parameters.cpp VerilogParameter::literal is the packer every generated build uses;
# this one serves the hand-written unit configurations of cmake/rtl_units.cmake and the Yosys
# checks of cmake/rtl.cmake, whose RTL tests would fail if the two disagreed. Which field is in
# which slot: the unit's row in model/specular_units.cpp and the decode at the top of its module.
set(SPEC_SLOTS 8)       # shade_pkg::SpecSlots
set(SPEC_SLOT_BITS 32)  # shade_pkg::SpecSlotW (8 hex digits)
function(spec_params_literal out)
  list(LENGTH ARGN n)
  if(n GREATER SPEC_SLOTS)
    message(FATAL_ERROR "spec_params_literal: ${n} slots given, SPEC_PARAMS has ${SPEC_SLOTS}")
  endif()
  set(hex "")
  foreach(k RANGE 1 ${SPEC_SLOTS})
    math(EXPR slot "${SPEC_SLOTS} - ${k}")
    set(v 0)
    if(slot LESS n)
      list(GET ARGN ${slot} v)
    endif()
    math(EXPR digits "${v}" OUTPUT_FORMAT HEXADECIMAL)
    string(REGEX REPLACE "^0x" "" digits "${digits}")
    string(LENGTH "${digits}" len)
    while(len LESS 8)
      set(digits "0${digits}")
      string(LENGTH "${digits}" len)
    endwhile()
    string(APPEND hex "${digits}")
  endforeach()
  math(EXPR width "${SPEC_SLOTS} * ${SPEC_SLOT_BITS}")
  set(${out} "${width}'h${hex}" PARENT_SCOPE)
endfunction()
