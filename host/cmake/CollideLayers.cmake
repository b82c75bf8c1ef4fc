# The host's folders as layers (docs/host.md, "Layers").
#
# collide_layer(<folder> [SOURCES <file>...] [USES <layer>...] [LIBS <target>...])
#   Builds host/<folder> into the static library layer_<folder> (an INTERFACE library when
#   it has no sources) that links the layers it USES and the LIBS it names. Each USES layer
#   must be declared before, so the layers form an acyclic graph by construction. The rule
#   is recorded: <folder> may include "<folder>/..." and "<used>/..." only, and <ode/...>
#   only if ODE is in its link closure (LIBS PkgConfig::ODE here or in a used layer).
#
# collide_add_layer_check()
#   Writes the recorded rules to ${CMAKE_BINARY_DIR}/collide_layers.txt, which the ctest
#   host.layers (cmake/check_layers.cmake) checks every source against.

function(collide_layer folder)
  cmake_parse_arguments(L "" "" "SOURCES;USES;LIBS" ${ARGN})
  if(NOT IS_DIRECTORY "${COLLIDE_HOST_DIR}/${folder}")
    message(FATAL_ERROR "collide_layer(${folder}): there is no folder host/${folder}")
  endif()
  set(ode 0)
  if("PkgConfig::ODE" IN_LIST L_LIBS)
    set(ode 1)
  endif()
  foreach(u ${L_USES})
    if(NOT TARGET layer_${u})
      message(FATAL_ERROR "collide_layer(${folder}): it uses ${u}, which is not declared before it "
                          "(declare layers bottom-up: that keeps them acyclic)")
    endif()
    get_property(u_ode GLOBAL PROPERTY COLLIDE_LAYER_ODE_${u})
    if(u_ode)
      set(ode 1)
    endif()
  endforeach()
  set(target layer_${folder})
  if(L_SOURCES)
    add_library(${target} STATIC ${L_SOURCES})
    set(scope PUBLIC)
  else()
    add_library(${target} INTERFACE)
    set(scope INTERFACE)
  endif()
  # The generated contract (afu_contract.hpp) is a leaf header every layer may read.
  target_include_directories(${target} ${scope} ${COLLIDE_HOST_DIR} ${COLLIDE_REPO_ROOT}/generated)
  list(TRANSFORM L_USES PREPEND layer_ OUTPUT_VARIABLE used_targets)
  target_link_libraries(${target} ${scope} ${used_targets} ${L_LIBS})
  set_property(GLOBAL PROPERTY COLLIDE_LAYER_ODE_${folder} ${ode})
  string(REPLACE ";" "," uses "${L_USES}")
  set_property(GLOBAL APPEND PROPERTY COLLIDE_LAYER_RULES "${folder}|${uses}|${ode}")
endfunction()

function(collide_add_layer_check)
  get_property(rules GLOBAL PROPERTY COLLIDE_LAYER_RULES)
  string(REPLACE ";" "\n" text "${rules}")
  file(WRITE "${CMAKE_BINARY_DIR}/collide_layers.txt"
       "# <folder>|<layers it uses>|<1: ODE linked>, written by host/cmake/CollideLayers.cmake\n${text}\n")
endfunction()
