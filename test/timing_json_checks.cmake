# collide_read_timing (host/cmake/CollideTiming.cmake): a folder's timing.json is compiled in only
# for the Verilog it names by SHA-256; otherwise the reason is given and the text is empty.
#   cmake -DHOST=<host dir> -DWORK=<scratch dir> -P timing_json_checks.cmake
include(${HOST}/cmake/CollideTiming.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_note dir sv pattern)
  collide_read_timing(${dir} "${sv}" text note)
  if(pattern STREQUAL "")
    if(NOT note STREQUAL "" OR text STREQUAL "")
      message(FATAL_ERROR "${dir}: want the timing compiled in; note '${note}'")
    endif()
  elseif(NOT text STREQUAL "" OR NOT note MATCHES "${pattern}")
    message(FATAL_ERROR "${dir}: want no timing and a note matching '${pattern}'; got note '${note}'")
  endif()
endfunction()

file(WRITE ${WORK}/Afu_x.sv "module Afu_x; endmodule\n")
file(SHA256 ${WORK}/Afu_x.sv sha)
set(json "{\"verilog\": {\"Afu_x.sv\": \"${sha}\"}, \"families\": {}}")

expect_note(${WORK} "${WORK}/Afu_x.sv" "has no timing.json")
file(WRITE ${WORK}/timing.json "${json}")
expect_note(${WORK} "${WORK}/Afu_x.sv" "")
file(APPEND ${WORK}/Afu_x.sv "// changed\n")
expect_note(${WORK} "${WORK}/Afu_x.sv" "describes another Afu_x.sv \\(stale")
file(WRITE ${WORK}/Afu_x.sv "module Afu_x; endmodule\n")
file(WRITE ${WORK}/Other.sv "module Other; endmodule\n")
expect_note(${WORK} "${WORK}/Afu_x.sv;${WORK}/Other.sv" "names 1 Verilog files, the folder has 2")
file(WRITE ${WORK}/timing.json "{\"families\": {}}")
expect_note(${WORK} "${WORK}/Afu_x.sv" "no verilog hashes")
message(STATUS "timing.json checks passed")
