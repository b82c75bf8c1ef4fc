# Verilating AFUs for the host (docs/host.md, "Plugging in the AFU").
#
# collide_verilate(<target> SOURCES <sv>... TOP <module> PREFIX <class> [TRACE OFF|VCD|FST] [OPT_FAST <flag>] [ARGS ...])
#   Adds the Verilated model V<prefix> to <target>. Verilator reruns only when a source
#   (or the command) changes; the C++ is compiled with COLLIDE_VERILATOR_OPT_FAST on the
#   per-cycle code (OPT_FAST overrides it) and -O0 on the construction/trace code (-O2
#   everywhere makes builds of big models take many minutes; docs/host.md, "The Verilator
#   harness", has the measured times), split in chunks so both cores compile at once.
#
# collide_add_afu_library(<target> <preset> <trace>)
#   Defines <target>, the library that implements driver/afu_factory.hpp:
#   - COLLIDE_AFU_DIR set: the generated AFU in that folder (e.g. a scratch copy);
#   - else <preset> set:   ${COLLIDE_REPO_ROOT}/generated/<preset>;
#   - else:                driver/no_afu.cpp (makeAfuPort() throws AfuUnavailable).
#   The top module comes from the folder's manifest.json `topModule`; the
#   manifest text is compiled in, so `makeAfuPort(dir)` refuses a folder whose manifest
#   differs. <trace>: OFF, VCD or FST (ON means FST).
#
# collide_add_afu_library_from_dir(<target> <dir> <preset> <trace> [<opt_fast>])
#   The same for an explicit folder (used by the tests for their own AFUs); <opt_fast> overrides
#   COLLIDE_VERILATOR_OPT_FAST for this model.

include("${CMAKE_CURRENT_LIST_DIR}/CollideTiming.cmake")

set(COLLIDE_VERILATOR_OPT_FAST "-O1" CACHE STRING
    "C++ optimisation of the Verilated per-cycle code (-O1 builds a big AFU far quicker than -O2/-O3)")
set(COLLIDE_VERILATOR_THREADS "1" CACHE STRING
    "Threads of the Verilated model (Verilator --threads; bench/verilator measures what more buys)")

function(collide_find_verilator)
  if(NOT COMMAND verilate)
    find_package(verilator 5 REQUIRED HINTS $ENV{VERILATOR_ROOT} /usr/share/verilator)
  endif()
endfunction()

function(collide_verilate target)
  cmake_parse_arguments(CV "" "TOP;PREFIX;TRACE;OPT_FAST" "SOURCES;ARGS" ${ARGN})
  if(NOT CV_OPT_FAST)
    set(CV_OPT_FAST ${COLLIDE_VERILATOR_OPT_FAST})
  endif()
  collide_find_verilator()
  string(TOUPPER "${CV_TRACE}" trace)
  set(trace_kw "")
  if(trace STREQUAL "VCD")
    set(trace_kw TRACE)
  elseif(trace STREQUAL "FST" OR trace STREQUAL "ON")
    set(trace_kw TRACE_FST)
  elseif(NOT trace STREQUAL "" AND NOT trace STREQUAL "OFF")
    message(FATAL_ERROR "collide_verilate: TRACE must be OFF, VCD or FST, got '${CV_TRACE}'")
  endif()
  # -w: the generated C++ is not ours to warn about (the project builds with -Wall -Wextra).
  set(threads_kw "")
  if(NOT COLLIDE_VERILATOR_THREADS STREQUAL "1")
    set(threads_kw THREADS ${COLLIDE_VERILATOR_THREADS})
  endif()
  # Under COLLIDE_SANITIZE the generated model is built plain (no sanitizer, no debug info):
  # it is Verilator's code, not ours, and instrumenting it made a world AFU's build take
  # most of an hour; the harness around it (verilated_afu_port.cpp) stays instrumented.
  set(plain "")
  if(COLLIDE_SANITIZE)
    set(plain -fno-sanitize=all -g0)
  endif()
  verilate(${target} SOURCES ${CV_SOURCES} TOP_MODULE ${CV_TOP} PREFIX ${CV_PREFIX} ${trace_kw} ${threads_kw}
           VERILATOR_ARGS -Wno-fatal -Wno-lint -Wno-style --x-assign fast --x-initial fast
                          --output-split 20000 --output-split-cfuncs 20000 -I${COLLIDE_REPO_ROOT}/generated ${CV_ARGS}
           OPT_FAST ${CV_OPT_FAST} -w ${plain}
           OPT_SLOW -O0 -w ${plain}
           OPT_GLOBAL -O2 -w ${plain})
  # Verilator's headers as system headers: our own -Wall -Wextra stays on our code.
  target_include_directories(${target} SYSTEM PRIVATE "${VERILATOR_ROOT}/include" "${VERILATOR_ROOT}/include/vltstd")
endfunction()

# The manifest's `topModule` (as collide.afu.AfuManifest writes it; `top` also accepted;
# default Afu_<folder name>) and `name` (the preset; default: the folder's name).
function(collide_read_manifest dir out_top out_preset)
  get_filename_component(preset "${dir}" NAME)
  set(top "Afu_${preset}")
  if(EXISTS "${dir}/manifest.json")
    file(READ "${dir}/manifest.json" manifest)
    foreach(key top topModule)
      string(JSON t ERROR_VARIABLE no_top GET "${manifest}" ${key})
      if(NOT no_top)
        set(top "${t}")
      endif()
    endforeach()
    string(JSON p ERROR_VARIABLE no_preset GET "${manifest}" "name")
    if(NOT no_preset)
      set(preset "${p}")
    endif()
  endif()
  set(${out_top} "${top}" PARENT_SCOPE)
  set(${out_preset} "${preset}" PARENT_SCOPE)
endfunction()

function(collide_add_afu_library_from_dir target gen_dir preset trace)
  set(opt_fast "${ARGV4}")
  file(GLOB afu_sv CONFIGURE_DEPENDS "${gen_dir}/*.sv" "${gen_dir}/*.v")
  if(NOT afu_sv)
    message(FATAL_ERROR "AFU ${gen_dir}: no Verilog (*.sv, *.v) there; run the generator first")
  endif()
  if(NOT EXISTS "${gen_dir}/manifest.json")
    message(FATAL_ERROR "AFU ${gen_dir}: no manifest.json (the generator writes one beside the Verilog)")
  endif()
  collide_read_manifest("${gen_dir}" top manifest_preset)
  if(preset STREQUAL "")
    set(preset "${manifest_preset}")
  endif()
  # The manifest, compiled in: makeAfuPort() compares it with the folder it is given.
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${gen_dir}/manifest.json")
  file(READ "${gen_dir}/manifest.json" COLLIDE_MANIFEST_TEXT)
  collide_read_timing("${gen_dir}" "${afu_sv}" COLLIDE_TIMING_TEXT COLLIDE_TIMING_NOTE)
  set(manifest_cpp "${CMAKE_CURRENT_BINARY_DIR}/${target}_manifest.cpp")
  file(CONFIGURE OUTPUT "${manifest_cpp}" @ONLY CONTENT
"// Generated by CollideVerilate.cmake from ${gen_dir}/manifest.json (and timing.json)
namespace collide::driver {
const char* collideBuiltInManifest() { return R\"collide_manifest(@COLLIDE_MANIFEST_TEXT@)collide_manifest\"; }
const char* collideBuiltInTiming() { return R\"collide_timing(@COLLIDE_TIMING_TEXT@)collide_timing\"; }
const char* collideBuiltInTimingNote() { return R\"collide_timing(@COLLIDE_TIMING_NOTE@)collide_timing\"; }
}
")
  # OBJECT: the seam's objects go into the executable itself, so makeAfuPort() is there for
  # every layer that calls it, whatever the order of the static layers on the link line.
  # scpu_model_dpi.cpp: the C++ SCPU behind a model AFU's SCPUs (--scpu-impl model); unused otherwise.
  add_library(${target} OBJECT "${COLLIDE_HOST_DIR}/driver/verilated_afu_port.cpp"
                               "${COLLIDE_HOST_DIR}/driver/scpu_model_dpi.cpp" "${manifest_cpp}")
  target_include_directories(${target} PRIVATE "${COLLIDE_HOST_DIR}")
  target_link_libraries(${target} PUBLIC collide_core)
  target_compile_definitions(${target} PRIVATE
    COLLIDE_AFU_PRESET="${preset}" COLLIDE_AFU_DIR="${gen_dir}"
    COLLIDE_AFU_VTOP=V${top} COLLIDE_AFU_VTOP_HEADER="V${top}.h")
  collide_verilate(${target} SOURCES ${afu_sv} TOP ${top} PREFIX V${top} TRACE ${trace} OPT_FAST "${opt_fast}")
  message(STATUS "AFU: ${gen_dir} (top ${top}, preset ${preset}, trace ${trace}) Verilated into ${target}")
endfunction()

function(collide_add_afu_library target preset trace)
  if(NOT TARGET collide_no_afu)  # also what tests link when they bring their own AfuPort
    add_library(collide_no_afu OBJECT "${COLLIDE_HOST_DIR}/driver/no_afu.cpp")
    target_include_directories(collide_no_afu PRIVATE "${COLLIDE_HOST_DIR}")
    target_link_libraries(collide_no_afu PUBLIC collide_core)
  endif()
  if(NOT COLLIDE_AFU_DIR STREQUAL "")
    get_filename_component(dir "${COLLIDE_AFU_DIR}" ABSOLUTE)
    collide_add_afu_library_from_dir(${target} "${dir}" "" ${trace})
  elseif(NOT preset STREQUAL "")
    collide_add_afu_library_from_dir(${target} "${COLLIDE_REPO_ROOT}/generated/${preset}" "${preset}" ${trace})
  else()
    add_library(${target} ALIAS collide_no_afu)
  endif()
endfunction()
