# The netlist is the circuit: `shadesim regress --netlist` simulates Yosys's
# gate-level netlist of a unit (the flat netlist `shadesim area` measures) in place of the RTL,
# bit and cycle exact against the model, on one small unit per specular kind
# (tests/netlist/*_small.json: ideal and none on sphere, which has no highlights; lut, schlick
# and wpow on both). Then a deliberately broken netlist must fail: a copy of the wpow
# unit's cached netlist with one gate inverted (the gate that drives the D input of
# pix_colour_o[0], the LSB of every pixel's colour), in a netlist cache of its own, must give a
# mismatch.
#   cmake -DCLI=shadesim -DSRC=source -DWORK=folder -DCACHE=rtl-cache -DNETLISTS=netlist-cache
#         -P netlist_check.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(cfg ${SRC}/tests/netlist)
execute_process(COMMAND ${CLI} regress ${SRC}/scenes/sphere.json ${SRC}/scenes/specular.json
                        --config ${cfg}/ideal_small.json --config ${cfg}/lut_small.json
                        --config ${cfg}/schlick_small.json --config ${cfg}/wpow_small.json
                        --config ${cfg}/none_small.json --netlist --netlist-cache ${NETLISTS} --backends cpp --jobs 2
                        --out ${WORK}/good --cache ${CACHE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
# 10 runs: ideal on specular is skipped (its RTL slot outputs 0 and the scene has highlights;
# none has no slot, and its model shades without highlights too).
if(NOT rc EQUAL 0 OR NOT out MATCHES "regress: 9 passed, 0 mismatched")
  message(FATAL_ERROR "regress --netlist on the small units failed (rc ${rc}):\n${out}\n${err}")
endif()
foreach(kind ideal lut schlick wpow none)
  if(NOT out MATCHES "netlist of [^\n]*${kind}_small.json: [^\n]*GE")
    message(FATAL_ERROR "regress --netlist did not name the ${kind} unit's netlist:\n${out}")
  endif()
endforeach()
message(STATUS "every specular kind's netlist passed")

# The wpow unit's netlist, copied with its stat into a cache of its own, one gate inverted.
if(NOT out MATCHES "netlist of [^\n]*wpow_small.json: ([^ \n]+netlist-[0-9a-f]+)\\.v ")
  message(FATAL_ERROR "no wpow netlist path in:\n${out}")
endif()
set(stem ${CMAKE_MATCH_1})
get_filename_component(name ${stem} NAME)
file(MAKE_DIRECTORY ${WORK}/broken-cache)
file(COPY ${stem}.json DESTINATION ${WORK}/broken-cache)
file(READ ${stem}.v text)
# The flip-flop pix_colour_o[0] <= D (out_reg's register, named "\u_out_reg.pix_colour_o [0]"
# in the flat netlist); the gate driving D gets its output inverted.
if(NOT text MATCHES "pix_colour_o ?\\[0\\] <= ([^;]+);")
  message(FATAL_ERROR "${stem}.v: no flip-flop drives pix_colour_o[0]")
endif()
set(d "${CMAKE_MATCH_1}")
string(FIND "${text}" "assign ${d} = " at)
if(at LESS 0)
  message(FATAL_ERROR "${stem}.v: no gate drives ${d}")
endif()
string(LENGTH "assign ${d} = " len)
math(EXPR rhs "${at} + ${len}")
string(SUBSTRING "${text}" 0 ${rhs} head)
string(SUBSTRING "${text}" ${rhs} -1 tail)
string(FIND "${tail}" ";" semi)
string(SUBSTRING "${tail}" 0 ${semi} gate)
string(SUBSTRING "${tail}" ${semi} -1 rest)
file(WRITE ${WORK}/broken-cache/${name}.v "${head}~(${gate})${rest}")
message(STATUS "broken: assign ${d} = ~(${gate})")

execute_process(COMMAND ${CLI} regress ${SRC}/scenes/specular.json --config ${cfg}/wpow_small.json
                        --netlist --netlist-cache ${WORK}/broken-cache --backends cpp --jobs 2
                        --out ${WORK}/broken --cache ${CACHE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT out MATCHES "regress: 0 passed, 1 mismatched")
  message(FATAL_ERROR "the broken netlist was not caught (rc ${rc}):\n${out}\n${err}")
endif()
if(NOT out MATCHES "${name}")
  message(FATAL_ERROR "the broken run did not use the edited netlist ${name}:\n${out}")
endif()
message(STATUS "the broken netlist fails: mismatch")
