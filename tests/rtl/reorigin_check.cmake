# Re-origined triangles through the RTL: multi's own unit (`shadesim config`) with its span
# setup offsets cut to 4 bits (-8..7, where its spans start up to 60 px from their triangles'
# centroid pixels), so the encoder splits triangles into several origins; `regress` must pass
# bit and cycle exact, and `render` must report the re-origins (else this tests nothing).
#   cmake -DCLI=shadesim -DSRC=source -DWORK=folder -DCACHE=rtl-cache -P reorigin_check.cmake
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CLI} config ${SRC}/scenes/multi.json --clock-mhz 0 --json ${WORK}/own.json
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "shadesim config scenes/multi.json failed (${rc})")
endif()
file(READ ${WORK}/own.json unit)
string(JSON unit SET "${unit}" offset_bits 4)
file(WRITE ${WORK}/ofs4.json "${unit}")
execute_process(COMMAND ${CLI} render ${SRC}/scenes/multi.json --config ${WORK}/ofs4.json
                        -o ${WORK}/render
                OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT out MATCHES "; ([1-9][0-9]*) re-origin\\(s\\) \\(offset_bits 4\\)")
  message(FATAL_ERROR "render on 4-bit offsets: expected re-origins (rc ${rc}):\n${out}")
endif()
message(STATUS "${CMAKE_MATCH_1} re-origined triangle(s)")
execute_process(COMMAND ${CLI} regress ${SRC}/scenes/multi.json --config ${WORK}/ofs4.json
                        --backends cpp --out ${WORK}/regress --cache ${CACHE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "regress: 1 passed, 0 mismatched")
  message(FATAL_ERROR "regress on 4-bit offsets failed (rc ${rc}):\n${out}\n${err}")
endif()
