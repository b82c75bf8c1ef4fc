# collide_add_afu_library(<target> <preset> <trace>)
#
# Defines <target>, the library that implements driver/afu_factory.hpp.
# - preset empty: the target is driver/no_afu.cpp; makeAfuPort() throws AfuUnavailable.
# - preset set:   Verilates ${COLLIDE_REPO_ROOT}/generated/<preset>/*.sv (top from the
#   manifest, default "CollideAfu") with verilate(), which reruns only when the Verilog
#   changes, and adds driver/verilated_afu_port.cpp (to be written with the AFU: it wraps
#   V<top> as an AfuPort). With <trace> ON the model gets --trace and the adapter can dump
#   a VCD (COLLIDE_AFU_TRACE compile definition).
function(collide_add_afu_library target preset trace)
  if(preset STREQUAL "")
    add_library(${target} STATIC ${CMAKE_CURRENT_SOURCE_DIR}/driver/no_afu.cpp)
    return()
  endif()

  set(gen_dir "${COLLIDE_REPO_ROOT}/generated/${preset}")
  file(GLOB afu_sv CONFIGURE_DEPENDS "${gen_dir}/*.sv" "${gen_dir}/*.v")
  if(NOT afu_sv)
    message(FATAL_ERROR "COLLIDE_AFU_PRESET=${preset}: no Verilog in ${gen_dir}; run the generator first")
  endif()
  set(adapter "${CMAKE_CURRENT_SOURCE_DIR}/driver/verilated_afu_port.cpp")
  if(NOT EXISTS "${adapter}")
    message(FATAL_ERROR "COLLIDE_AFU_PRESET=${preset}: ${adapter} (the AfuPort adapter) is not written yet")
  endif()
  set(top "CollideAfu")
  if(EXISTS "${gen_dir}/manifest.json")
    file(READ "${gen_dir}/manifest.json" manifest)
    string(JSON top_from_manifest ERROR_VARIABLE no_top GET "${manifest}" "top")
    if(NOT no_top)
      set(top "${top_from_manifest}")
    endif()
  endif()

  find_package(verilator 5 REQUIRED HINTS $ENV{VERILATOR_ROOT} /usr/share/verilator)
  add_library(${target} STATIC "${adapter}")
  target_include_directories(${target} PRIVATE "${gen_dir}")
  target_compile_definitions(${target} PRIVATE COLLIDE_AFU_PRESET="${preset}"
                                               COLLIDE_AFU_DIR="${gen_dir}")
  set(trace_args "")
  if(trace)
    set(trace_args TRACE)
    target_compile_definitions(${target} PRIVATE COLLIDE_AFU_TRACE=1)
  endif()
  # OPT_FAST only (NOTES.md: -O2 everywhere makes Verilator builds take minutes).
  verilate(${target} SOURCES ${afu_sv} TOP_MODULE ${top} PREFIX V${top}
           ${trace_args} VERILATOR_ARGS -Wno-fatal --x-assign fast --x-initial fast
           OPT_FAST -O2 OPT_SLOW -O0)
endfunction()
