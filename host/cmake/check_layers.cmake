# The ctest host.layers: every host source keeps to its layer's rules (docs/host.md, "Layers").
#   cmake -DRULES=<build>/collide_layers.txt -DHOST=<repo>/host -P check_layers.cmake
# Fails, naming each file and include, when a source
#   - includes "<folder>/..." of a host folder its layer does not declare in USES,
#   - includes <ode/...> in a layer whose link closure has no ODE,
# or when a folder of host/ is no layer at all (its sources would be checked by nothing).
cmake_minimum_required(VERSION 3.20)  # IN_LIST and the other policies of the build
if(NOT EXISTS "${RULES}" OR NOT IS_DIRECTORY "${HOST}")
  message(FATAL_ERROR "check_layers: need -DRULES=<collide_layers.txt> and -DHOST=<host folder>; got '${RULES}', '${HOST}'")
endif()

file(STRINGS "${RULES}" rules REGEX "^[^#]")
set(layers "")
foreach(rule ${rules})
  if(NOT rule MATCHES "^([a-z_0-9]+)\\|([a-z_0-9,]*)\\|([01])$")
    message(FATAL_ERROR "check_layers: ${RULES}: cannot read the rule '${rule}'")
  endif()
  list(APPEND layers ${CMAKE_MATCH_1})
  string(REPLACE "," ";" uses_${CMAKE_MATCH_1} "${CMAKE_MATCH_2}")
  set(ode_${CMAKE_MATCH_1} ${CMAKE_MATCH_3})
endforeach()

file(GLOB entries LIST_DIRECTORIES true RELATIVE "${HOST}" "${HOST}/*")
set(folders "")
foreach(e ${entries})
  if(IS_DIRECTORY "${HOST}/${e}" AND NOT e STREQUAL "cmake")  # cmake/: the build's own scripts
    list(APPEND folders ${e})
  endif()
endforeach()

set(problems "")
foreach(folder ${folders})
  if(NOT folder IN_LIST layers)
    list(APPEND problems "host/${folder}/: not a layer (declare it with collide_layer in host/CMakeLists.txt)")
    continue()
  endif()
  file(GLOB_RECURSE sources RELATIVE "${HOST}" "${HOST}/${folder}/*.hpp" "${HOST}/${folder}/*.cpp" "${HOST}/${folder}/*.h")
  foreach(src ${sources})
    file(STRINGS "${HOST}/${src}" includes REGEX "^[ \t]*#[ \t]*include")
    foreach(inc ${includes})
      if(inc MATCHES "include[ \t]*\"([a-z_0-9]+)/")
        set(to ${CMAKE_MATCH_1})
        if(NOT to STREQUAL folder AND to IN_LIST folders AND NOT to IN_LIST uses_${folder})
          string(REPLACE ";" ", " allowed "${uses_${folder}}")
          list(APPEND problems "host/${src}: ${inc}: layer ${folder} does not use ${to} (it uses: ${allowed})")
        endif()
      elseif(inc MATCHES "include[ \t]*<ode/" AND NOT ode_${folder})
        list(APPEND problems "host/${src}: ${inc}: layer ${folder} is ODE-free (no ODE in its link closure)")
      endif()
    endforeach()
  endforeach()
endforeach()

list(LENGTH problems n)
if(n GREATER 0)
  string(REPLACE ";" "\n  " text "${problems}")
  message(FATAL_ERROR "check_layers: ${n} problem(s):\n  ${text}")
endif()
list(LENGTH layers nl)
message(STATUS "check_layers: ${nl} layers, every include of host/ keeps to them")
