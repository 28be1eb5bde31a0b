# The Icarus testbench must mirror every parameter of shade_unit: iverilog -P sets parameters
# of the root module only, so a shade_unit parameter the testbench lacks could never be set from
# a configuration (and a named build that needs it would run the RTL's default). This check
# reads both parameter lists and fails, naming the parameter, when
#   - shade_unit declares a parameter the testbench does not (or the other way round),
#   - their defaults differ (an unset parameter must mean the same in both), or
#   - the testbench does not pass it on to its shade_unit instance (.NAME(NAME)).
#
#   cmake -DRTL_TOP=rtl/shade_unit.sv -DTB=sim/icarus/tb_shade_unit.sv [-DINJECT=NAME]
#         -P sim/icarus/tb_params_check.cmake
#
# INJECT=NAME adds "parameter int NAME = 0" to shade_unit's list as read, so a test can show the
# check fails when shade_unit gains a parameter.
cmake_minimum_required(VERSION 3.18)  # IN_LIST, string(JSON) in script mode
foreach(var RTL_TOP TB)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "tb_params_check: -D${var}=... is required")
  endif()
endforeach()

# The parameter port list "module NAME #( ... \n)" of `file`: NAME;default pairs in `out_names`
# (names) and `out_defaults` (defaults, the same order), comments and spaces removed.
function(read_parameters file module out_names out_defaults)
  file(READ ${file} text)
  string(FIND "${text}" "module ${module} #(" start)
  if(start EQUAL -1)
    message(FATAL_ERROR "tb_params_check: ${file}: no \"module ${module} #(\" parameter list")
  endif()
  string(SUBSTRING "${text}" ${start} -1 text)
  string(FIND "${text}" "\n)" stop)
  if(stop EQUAL -1)
    message(FATAL_ERROR "tb_params_check: ${file}: the parameter list of ${module} has no closing \")\" line")
  endif()
  string(SUBSTRING "${text}" 0 ${stop} text)
  string(REGEX REPLACE "//[^\n]*" "" text "${text}")
  string(REPLACE ";" "" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(names "")
  set(defaults "")
  foreach(line ${lines})
    # "int" or a packed type ("logic [W-1:0]", SPEC_PARAMS) before the name.
    if(line MATCHES "^[ \t]*parameter[ \t]+(int[ \t]+|logic[ \t]*\\[[^=]*\\][ \t]*)?([A-Za-z_][A-Za-z0-9_]*)[ \t]*=[ \t]*([^,]*[^, \t])[ \t]*,?[ \t]*$")
      list(APPEND names ${CMAKE_MATCH_2})
      string(REGEX REPLACE "[ \t]+" "" d "${CMAKE_MATCH_3}")
      list(APPEND defaults "${d}")
    elseif(line MATCHES "parameter")
      message(FATAL_ERROR "tb_params_check: ${file}: cannot read this parameter line of ${module} "
                          "(expected \"parameter [int | logic [..]] NAME = DEFAULT,\"):\n${line}")
    endif()
  endforeach()
  set(${out_names} "${names}" PARENT_SCOPE)
  set(${out_defaults} "${defaults}" PARENT_SCOPE)
endfunction()

read_parameters(${RTL_TOP} shade_unit rtl_names rtl_defaults)
read_parameters(${TB} tb_shade_unit tb_names tb_defaults)
if(INJECT)
  list(APPEND rtl_names ${INJECT})
  list(APPEND rtl_defaults 0)
endif()
list(LENGTH rtl_names n_rtl)
if(n_rtl LESS 10)
  message(FATAL_ERROR "tb_params_check: read only ${n_rtl} parameters of shade_unit from ${RTL_TOP}: "
                      "the parser no longer matches its parameter list")
endif()

file(READ ${TB} tb_text)
set(errors "")
foreach(name IN LISTS rtl_names)
  list(FIND rtl_names ${name} i)
  list(GET rtl_defaults ${i} rtl_default)
  list(FIND tb_names ${name} j)
  if(j EQUAL -1)
    string(APPEND errors "  shade_unit parameter ${name} (default ${rtl_default}) is not declared by tb_shade_unit\n")
    continue()
  endif()
  list(GET tb_defaults ${j} tb_default)
  if(NOT tb_default STREQUAL rtl_default)
    string(APPEND errors "  ${name}: default ${rtl_default} in shade_unit, ${tb_default} in tb_shade_unit\n")
  endif()
  if(NOT tb_text MATCHES "\\.${name}\\(${name}\\)")
    string(APPEND errors "  ${name}: tb_shade_unit does not pass it on to shade_unit (.${name}(${name}))\n")
  endif()
endforeach()
# The testbench's own parameters (its memory and run limits, and the fault hooks it instantiates
# beside the unit) are not shade_unit's.
set(tb_own MAX_WORDS DRAIN_CYCLES HANG_CYCLES FAULT_HOOKS)
foreach(name IN LISTS tb_names)
  if(NOT name IN_LIST rtl_names AND NOT name IN_LIST tb_own)
    string(APPEND errors "  tb_shade_unit declares ${name}, which shade_unit does not have\n")
  endif()
endforeach()
if(errors)
  message(FATAL_ERROR "tb_params_check: ${TB} does not mirror the parameters of ${RTL_TOP}:\n${errors}"
                      "Declare each shade_unit parameter in tb_shade_unit with the same default and pass it on.")
endif()
message(STATUS "tb_shade_unit mirrors all ${n_rtl} parameters of shade_unit")
