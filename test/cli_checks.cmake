# Runs the collide binary for one CLI check: cmake -DCOLLIDE=... -DCHECK=... -DWORK=... -DREPO=... -P
file(MAKE_DIRECTORY ${WORK})
function(expect_rc want)
  if(NOT rc EQUAL ${want})
    message(FATAL_ERROR "exit code ${rc}, expected ${want}\nstdout:\n${out}\nstderr:\n${err}")
  endif()
endfunction()
function(expect_match text regex)
  if(NOT "${text}" MATCHES "${regex}")
    message(FATAL_ERROR "expected output matching '${regex}', got:\n${text}")
  endif()
endfunction()
# The world the grid and engine checks share (bad spheres, touching and coincident pairs among
# them) in ${WORK}/in.csv, and simd's contacts for it in `want` (the caller's scope).
macro(simd_reference_world)
  file(WRITE ${WORK}/in.csv "x,y,z,r\n0,0,0,1\n0x1.8p+1,0,0,1\n 1.5 ,0,0,1\n\nnan,0,0,1\n0,0,0,-1\n-8,-8,-8,0.1\n-8,-8,-7.75,0.2\n0,0,0,0.5\n3,0,0,0.5\n40,40,40,30\n")
  execute_process(COMMAND ${COLLIDE} spheres --backend simd --in ${WORK}/in.csv --out ${WORK}/simd.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  file(READ ${WORK}/simd.csv want)
endmacro()
# A contacts file that must equal simd's (`want`), `what` naming the run in the failure.
function(expect_simd_contacts file what)
  file(READ ${file} got)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "${what}: contacts differ from simd's:\n--- got\n${got}--- want\n${want}")
  endif()
endfunction()

# Vector mode for a pair kind beyond spheres (docs/pair-kinds.md): `input` (CSV text) on simd,
# simd64 and ode, each exiting 0 with `summary` and the flagged line on stderr; simd64 equal to
# ODE's dCollide byte for byte, and simd's output `want_simd` exactly.
function(expect_kind_vector_mode kind input summary want_simd)
  file(WRITE ${WORK}/in.csv "${input}")
  foreach(backend simd simd64 ode)
    execute_process(COMMAND ${COLLIDE} pairs --kind ${kind} --backend ${backend} --in ${WORK}/in.csv --out ${WORK}/out-${backend}.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "${summary}")
    expect_match("${err}" "collide pairs: flagged")
  endforeach()
  file(READ ${WORK}/out-simd64.csv got)
  file(READ ${WORK}/out-ode.csv want)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "${kind}: simd64 differs from ode:\n--- got\n${got}--- want\n${want}")
  endif()
  file(READ ${WORK}/out-simd.csv got)
  if(NOT got STREQUAL want_simd)
    message(FATAL_ERROR "${kind}: simd contacts differ:\n--- got\n${got}--- want\n${want_simd}")
  endif()
endfunction()

set(pairs "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,1,0,0,0,2\n3,4,0,2,0,0,0,3\n0x1.8p+1,4,0,1,0,0,0,1\n")
if(CHECK STREQUAL "pairs_simd" OR CHECK STREQUAL "pairs_ode")
  string(REPLACE "pairs_" "" backend ${CHECK})
  file(WRITE ${WORK}/in.csv "${pairs}")
  execute_process(COMMAND ${COLLIDE} pairs --backend ${backend} --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  file(READ ${WORK}/out.csv got)
  # coincident: pos p1, normal (1,0,0), depth 3; grazing: hit with depth 0 and normal (0.6, 0.8, 0);
  # separated: hit 0. Hex floats in the link format.
  if(backend STREQUAL "simd")
    set(want "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,1,0x0p+0,0x0p+0,0x0p+0,0x1p+0,0x0p+0,0x0p+0,0x1.8p+1,5\n1,1,0x1.ccccccp+0,0x1.333334p+1,0x0p+0,0x1.333334p-1,0x1.99999ap-1,0x0p+0,0x0p+0,3\n2,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0\n")
  else()
    set(want "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,1,0x0p+0,0x0p+0,0x0p+0,0x1p+0,0x0p+0,0x0p+0,0x1.8p+1,5\n1,1,0x1.cccccccccccccp+0,0x1.3333333333333p+1,0x0p+0,0x1.3333333333334p-1,0x1.999999999999ap-1,0x0p+0,0x0p+0,3\n2,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0\n")
  endif()
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "contacts.csv differs:\n--- got\n${got}--- want\n${want}")
  endif()
elseif(CHECK STREQUAL "pairs_sphere_plane")
  # Sphere/plane vector mode (docs/pair-kinds.md): touching, sunk by half, a plane that ODE
  # normalizes, a negative radius, a NaN, a value beyond binary32, a radius that becomes zero in
  # binary32, a zero normal (ODE makes it (1, 0, 0, 0)).
  expect_kind_vector_mode(sphere-plane "cx,cy,cz,r,nx,ny,nz,d\n0,0,1,1,0,0,1,0\n0.25,-3,0.5,1,0,0,1,0\n10,10,10,1,1,1,1,1\n0,0,5,-1,0,0,1,0\nnan,0,0,1,0,0,1,0\n1e300,0,0,1,0,0,1,0\n0,0,1e-50,1e-50,0,0,1,0\n1,2,3,1,0,0,0,5\n"
    "8 sphere-plane pairs"
    "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,1,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x1p+0,0x0p+0,1\n1,1,0x1p-2,-0x1.8p+1,-0x1p-1,0x0p+0,0x0p+0,0x1p+0,0x1p-1,1\n2,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0\n3,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,32\n4,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,8\n5,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,40\n6,1,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x1p+0,0x0p+0,33\n7,1,0x0p+0,0x1p+1,0x1.8p+1,0x1p+0,0x0p+0,0x0p+0,0x0p+0,1\n")
  # Backends without sphere/plane pairs are refused, naming the kind.
  foreach(args "--backend;model:fp32" "--afu;${REPO}/generated/default")
    execute_process(COMMAND ${COLLIDE} pairs --kind sphere-plane ${args} --in ${WORK}/in.csv --out ${WORK}/x.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "--kind sphere-plane: ")
  endforeach()
elseif(CHECK STREQUAL "pairs_capsule_sphere")
  # Capsule/sphere vector mode (docs/pair-kinds.md): beside the middle, touching a cap, beyond
  # the other cap, centre on the axis (coincident), an axis ODE normalizes, a zero axis, a
  # negative length, a NaN, a radius that becomes zero in binary32.
  expect_kind_vector_mode(capsule-sphere "cx,cy,cz,ax,ay,az,lz,rc,sx,sy,sz,rs\n0,0,0,0,0,1,2,1,1.5,0,0,1\n0,0,0,0,0,1,2,1,0,0,3,1\n0,0,0,0,0,1,2,1,0.5,0,-2.5,1\n0,0,0,0,0,1,2,1,0,0,0.5,0.25\n1,1,1,1,1,1,4,0.5,2,1,1,0.75\n0,0,0,0,0,0,2,1,0,0,0,1\n0,0,0,0,0,1,-2,1,0,0,0,1\n0,0,0,0,0,1,2,1,nan,0,0,1\n0,0,0,0,0,1,2,1e-50,3,0,0,1\n"
    "9 capsule-sphere pairs, 5 contacts"
    "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,1,0x1.8p-1,0x0p+0,0x0p+0,-0x1p+0,0x0p+0,0x0p+0,0x1p-1,1\n1,1,0x0p+0,0x0p+0,0x1p+1,0x0p+0,0x0p+0,-0x1p+0,0x0p+0,1\n2,1,0x1p-2,0x0p+0,-0x1.cp+0,-0x1.43d136p-2,0x0p+0,0x1.e5b9dp-1,0x1.ace9fp-2,1\n3,1,0x0p+0,0x0p+0,0x1p-1,0x1p+0,0x0p+0,0x0p+0,0x1.4p+0,1\n4,1,0x1.9089ecp+0,0x1.37bb08p+0,0x1.37bb08p+0,-0x1.a20bdcp-1,0x1.a20bd2p-2,0x1.a20bd2p-2,0x1.bbe854p-2,1\n5,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,32\n6,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,32\n7,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,8\n8,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,32\n")
elseif(CHECK STREQUAL "model_backend")
  # model:<preset>: an AFU preset's SCPU on the CPU. model:fp32 is binary32 with correctly
  # rounded roots, as simd: the same output byte for byte.
  file(WRITE ${WORK}/in.csv "${pairs}")
  foreach(backend simd model:fp32)
    execute_process(COMMAND ${COLLIDE} pairs --backend ${backend} --in ${WORK}/in.csv --out ${WORK}/out-${backend}.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
  endforeach()
  file(READ ${WORK}/out-simd.csv want)
  file(READ ${WORK}/out-model:fp32.csv got)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "model:fp32 differs from simd:\n--- got\n${got}--- want\n${want}")
  endif()
  execute_process(COMMAND ${COLLIDE} pairs --backend model:fp32-nr --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(105)  # CLI11's ValidationError
  expect_match("${err}" "SCPU preset 'fp32-nr' is not emulated on the CPU: its roots are Newton-Raphson")
  # A scene in lasting contact, in binary16, with the physics line.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/rest_stack.json --backend model:fp16 --steps 3
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "backend model:fp16, link not simulated")
  expect_match("${out}" "physics      : kinetic energy at most [0-9.e+-]+ J \\(last step [0-9.e+-]+ J\\), deepest contact [0-9.]+ mm, 0 spheres through a plane")
elseif(CHECK STREQUAL "pairs_bad_line")
  file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,1,0,0,0,2\n1,2,3\n")
  execute_process(COMMAND ${COLLIDE} pairs --backend simd --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "in.csv:3: expected 8 fields, got 3")
elseif(CHECK STREQUAL "run_small")
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --steps 20 --out ${WORK}/steps.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "pairs tested : [1-9]")
  expect_match("${out}" "ODE collider : [0-9.]+ ms total, [0-9.]+ ns/pair")
  expect_match("${out}" "simd batch   : [0-9.]+ ms total")
  # The binary64 kernel beside it: ODE's arithmetic, so it never disagrees with ODE on a hit.
  expect_match("${out}" "simd64 batch : [0-9.]+ ms total")
  expect_match("${out}" "pairs disagree on hit \\(simd64: 0\\)")
  # Where the steps' time went, stage by stage (docs/host.md, "Where a step's time goes").
  expect_match("${out}" "time split   : [0-9.]+ ms in 20 steps")
  foreach(stage "broad phase" "narrow, sphere/sphere" "narrow, sphere/plane" "contact joints" "solver" "other")
    expect_match("${out}" "\n  ${stage} +-?[0-9.]+ ms +-?[0-9.]+ %")
  endforeach()
  file(STRINGS ${WORK}/steps.csv header LIMIT_COUNT 1)
  expect_match("${header}" ",hit_mismatches,broad_ns,plane_narrow_ns,joints_ns,solver_ns,step_ns,kinetic_j,max_depth_m,escaped$")
  file(STRINGS ${WORK}/steps.csv rows)
  list(LENGTH rows n)
  if(NOT n EQUAL 21)
    message(FATAL_ERROR "steps.csv has ${n} rows, expected header + 20")
  endif()
  # A clock times an AFU: on a CPU backend it is refused, naming the option, before any step.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --steps 1 --clock-mhz 50
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz applies to the AFU \\(--afu DIR or --backend rtl\\), not to backend simd")
elseif(CHECK STREQUAL "run_lasting_scenes")
  # Every lasting-contact scene loads and runs a few steps on every CPU backend, in contact.
  foreach(scene diamond_settle pile_box)
    foreach(backend simd simd64 ode)
      execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/${scene}.json --backend ${backend} --steps 3
                      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
      expect_rc(0)
      expect_match("${out}" "backend ${backend}, link not simulated")
      expect_match("${out}" "contacts     : [1-9][0-9][0-9][0-9]+ sphere/sphere")
    endforeach()
  endforeach()
  expect_match("${out}" "sphere/sphere \\(\\+[1-9][0-9]* sphere/plane on the CPU\\)")  # pile_box's box
elseif(CHECK STREQUAL "run_rtl_unavailable")
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --backend rtl
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(2)
  expect_match("${err}" "no AFU available")
elseif(CHECK STREQUAL "pairs_rtl_unavailable")
  file(WRITE ${WORK}/in.csv "${pairs}")
  file(MAKE_DIRECTORY ${WORK}/afu)
  execute_process(COMMAND ${COLLIDE} pairs --afu ${WORK}/afu --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(2)
  expect_match("${err}" "no AFU available")
elseif(CHECK STREQUAL "info_missing")
  execute_process(COMMAND ${COLLIDE} info --afu ${WORK}/nowhere
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "manifest.json: no manifest")
  file(MAKE_DIRECTORY ${WORK}/afu)
  file(WRITE ${WORK}/afu/manifest.json "{\"link\": {\"format\": \"binary32\"}, \"afu\": {\"maxSpheres\": 1024, \"scpus\": 16}}")
  execute_process(COMMAND ${COLLIDE} info --afu ${WORK}/afu
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "\"scpus\": 16")
elseif(CHECK STREQUAL "info_links")
  execute_process(COMMAND ${COLLIDE} info --links RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  foreach(name ideal harp2 pac cxl)
    expect_match("${out}" "\n${name}: ")
  endforeach()
  expect_match("${out}" "\nqpi \\(also harp1\\): HARP v1")
  expect_match("${out}" "clock 400 MHz \\(AFU port 25.6 GB/s a direction\\)")
  expect_match("${out}" "channel PCIe1: read 6.23 GB/s, write 6.26 GB/s; read latency 400-600 ns")
  expect_match("${out}" "together: read 20.46 GB/s, write 20.52 GB/s")
  expect_match("${out}" "per call: transaction overhead 5000 ns, CSR write 125 ns, poll 290 ns")
  expect_match("${out}" "HARP v2 characterisation, IEEE Access 2018")
  # info needs exactly one of --afu and --links
  foreach(args "" "--links;--afu;${WORK}")
    execute_process(COMMAND ${COLLIDE} info ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "collide info: give exactly one of --afu DIR .* or --links")
  endforeach()
elseif(CHECK STREQUAL "link_bad_name")
  file(WRITE ${WORK}/in.csv "${pairs}")
  foreach(cmd "pairs;--backend;simd;--in;${WORK}/in.csv;--out;${WORK}/out.csv" "run;${REPO}/scenes/small.json;--steps;1")
    execute_process(COMMAND ${COLLIDE} ${cmd} --link pcie RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      message(FATAL_ERROR "--link pcie accepted:\n${out}\n${err}")
    endif()
    expect_match("${err}" "--link: pcie not in {ideal,qpi,harp1,harp2,pac,cxl}")
  endforeach()
  # every preset name is accepted (a CPU backend: the link is parsed, not simulated)
  foreach(name ideal qpi harp1 harp2 pac cxl)
    execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --steps 1 --link ${name}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
  endforeach()
  # and a scene's link type: the key path and the known names
  file(WRITE ${WORK}/bad.json "{\"steps\": 1, \"dt\": 0.01, \"link\": {\"type\": \"pcie\"}, \"bodies\": {\"diamond\": {\"hMax\": 2}}}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/bad.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "scene.link.type: expected \"ideal\", \"qpi\", \"harp1\", \"harp2\", \"pac\" or \"cxl\", got \"pcie\"")
elseif(CHECK STREQUAL "td_pairs")
  # The collide CLI built with the TEST DOUBLE AFU: plumbing only (it answers "separated").
  file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,1,5,0,0,1\n0,0,0,0.5,0,0,9,0.25\n1,2,3,0.1,-1,-2,-3,0.1\n")
  foreach(mode compact dense)
    set(flags --link qpi)
    if(mode STREQUAL "dense")
      list(APPEND flags --dense --no-skip)
    endif()
    execute_process(COMMAND ${COLLIDE} pairs --afu ${TD_DIR} ${flags} --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "3 pairs, 0 contacts, backend rtl \\(binary32\\), 1 AFU runs, [1-9][0-9]* AFU cycles")
    file(READ ${WORK}/out.csv got)
    set(zero "0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0")
    set(want "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,0,${zero},0\n1,0,${zero},0\n2,0,${zero},0\n")
    if(NOT got STREQUAL want)
      message(FATAL_ERROR "${mode}: contacts.csv differs:\n--- got\n${got}--- want\n${want}")
    endif()
  endforeach()
elseif(CHECK STREQUAL "td_pairs_presets")
  # Every link preset drives the Verilated double: 400 MHz clocks and several channels too.
  file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,1,5,0,0,1\n0,0,0,0.5,0,0,9,0.25\n")
  foreach(link ideal harp1 harp2 pac cxl)
    execute_process(COMMAND ${COLLIDE} pairs --afu ${TD_DIR} --link ${link} --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    string(REPLACE "harp1" "qpi" canonical ${link})
    # The AFU's clock is the preset's: HARP v1's 200 MHz, CCI-P's 400 (collide info --links).
    set(mhz 400)
    if(link STREQUAL "ideal" OR link STREQUAL "harp1")
      set(mhz 200)
    endif()
    expect_match("${err}" "2 pairs, 0 contacts, backend rtl .* us modelled \\(link ${canonical} at ${mhz} MHz\\)")
  endforeach()
elseif(CHECK STREQUAL "td_pairs_wrong_afu")
  file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,1,5,0,0,1\n")
  file(MAKE_DIRECTORY ${WORK}/other)
  file(WRITE ${WORK}/other/manifest.json "{\"top\": \"CollideAfu\", \"link\": {\"format\": \"binary32\"}}")
  execute_process(COMMAND ${COLLIDE} pairs --afu ${WORK}/other --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(2)
  expect_match("${err}" "manifest.json differs from the AFU this collide was built with")
elseif(CHECK STREQUAL "td_run" OR CHECK STREQUAL "td_run_trace")
  # Spheres whose boxes overlap but which never touch: the broad phase sends pairs, the
  # double answers them all "separated", which is right here, so rtl and ode agree.
  set(extra "")
  if(CHECK STREQUAL "td_run_trace")
    set(extra --trace ${WORK}/run.fst --steps 3)
  endif()
  execute_process(COMMAND ${COLLIDE} run ${REPO}/test/scenes/apart_rtl.json --link qpi --per-step
                          --out ${WORK}/steps.csv --summary ${WORK}/summary.json ${extra}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "backend rtl, link qpi, AFU test-double")
  expect_match("${out}" "pairs tested : [1-9]")
  expect_match("${out}" "contacts     : 0 sphere/sphere")
  expect_match("${out}" "AFU \\(modelled, link qpi\\): [1-9][0-9]* runs")
  expect_match("${out}" "overhead +[0-9.]+ us")
  file(READ ${WORK}/summary.json summary)
  expect_match("${out}" "narrow, sphere/sphere +[0-9.]+ ms +[0-9.]+ %  \\(the AFU, modelled, link qpi")
  string(JSON split GET "${summary}" time_split narrow_modelled_ns)
  string(JSON runs GET "${summary}" afu runs)
  string(JSON ns GET "${summary}" afu modelled_ns)
  if(runs LESS 1 OR ns LESS 5000)
    message(FATAL_ERROR "summary.json: afu.runs ${runs}, afu.modelled_ns ${ns}")
  endif()
  if(CHECK STREQUAL "td_run_trace")
    if(NOT EXISTS ${WORK}/run.fst)
      message(FATAL_ERROR "no trace written")
    endif()
  endif()
elseif(CHECK STREQUAL "afu_run_diamond")
  # The real AFU on the diamond, two steps over the HARP v1 link.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/diamond.json --backend rtl --link qpi --steps 2
                          --summary ${WORK}/summary.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "pairs tested : 11658 ")
  expect_match("${out}" "AFU \\(modelled, link qpi\\): 2 runs")
elseif(CHECK STREQUAL "afu_run_pile_box")
  # The real AFU on a pile with a third of its pairs in contact, 40 steps over the HARP v1
  # link: writes back up and SCPUs of one group finish at different times. Before the fix in
  # ContactCollector a mask header here took bits of another group's results (the host's
  # decoder stopped the run at step 11-20); every pair must be accounted for.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box.json --backend rtl --link qpi --steps 40
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "AFU \\(modelled, link qpi\\): [1-9][0-9]* runs")
elseif(CHECK STREQUAL "afu_run_require")
  # collision.require (docs/pair-kinds.md): a kind the AFU has units for runs; one it lacks is
  # refused before any step, naming the kind and the AFU; the summary says where each kind went.
  set(scene "{\"name\": \"require\", \"steps\": 2, \"dt\": 0.01, \"effects\": {\"gravity\": [0, 0, -9.81], \"planes\": [{\"normal\": [0, 0, 1], \"offset\": 0}]}, \"collision\": {\"require\": [@KINDS@]}, \"bodies\": {\"spheres\": [{\"pos\": [0, 0, 0.5], \"r\": 0.6}, {\"pos\": [0, 0, 1.5], \"r\": 0.6}]}}")
  string(REPLACE "@KINDS@" "\"sphere-sphere\"" ok "${scene}")
  file(WRITE ${WORK}/ok.json "${ok}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/ok.json --backend rtl --summary ${WORK}/ok-summary.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  file(READ ${WORK}/ok-summary.json summary)
  string(JSON on GET "${summary}" pair_kinds sphere-plane on)
  string(JSON planePairs GET "${summary}" pair_kinds sphere-plane pairs)
  expect_match("${on}" "^ode")
  expect_match("${planePairs}" "^[1-9]")
  string(REPLACE "@KINDS@" "\"sphere-sphere\", \"sphere-plane\"" bad "${scene}")
  file(WRITE ${WORK}/bad.json "${bad}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/bad.json --backend rtl --out ${WORK}/steps.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "collision.require names sphere-plane, but the AFU built in \\(default\\) has units for sphere-sphere only")
  if(EXISTS ${WORK}/steps.csv)
    message(FATAL_ERROR "a refused run wrote steps.csv")
  endif()
elseif(CHECK STREQUAL "cosim_equals_rtl")
  # The RTL default AFU and cosim (its SCPUs the C++ model) on the same scenes over HARP v1 and
  # a hostile link: the same AFU counters to the cycle, the same modelled time, the same contacts
  # (so the same trajectory), and the same dense records of hard pairs.
  set(hostile "{\"type\": \"qpi\", \"read_latency_ns\": [5, 400], \"reorder\": true, \"ready_drop\": 0.3, \"seed\": 11}")
  file(READ ${REPO}/scenes/pile_box.json pile)
  string(JSON pile SET "${pile}" link "${hostile}")
  file(WRITE ${WORK}/pile_hostile.json "${pile}")
  foreach(scene "${REPO}/scenes/diamond_settle.json;30" "${WORK}/pile_hostile.json;8")
    list(GET scene 0 file)
    list(GET scene 1 steps)
    foreach(exe COLLIDE COSIM)
      # One clock for both: each binary would otherwise use what its own Verilog reaches.
      execute_process(COMMAND ${${exe}} run ${file} --backend rtl --steps ${steps} --clock-mhz 200 --summary ${WORK}/${exe}.json
                              --positions ${WORK}/${exe}_pos.csv
                      RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
      expect_rc(0)
      file(READ ${WORK}/${exe}.json j_${exe})
      file(READ ${WORK}/${exe}_pos.csv pos_${exe})
    endforeach()
    foreach(key contacts pairs)
      string(JSON a GET "${j_COLLIDE}" ${key})
      string(JSON b GET "${j_COSIM}" ${key})
      if(NOT a STREQUAL b)
        message(FATAL_ERROR "${file}: ${key} ${a} (RTL) != ${b} (cosim)")
      endif()
    endforeach()
    foreach(key runs modelled_ns cycles_total loading_ns computing_ns wait_read_ns wait_write_ns read_lines write_lines cycles_stepped)
      string(JSON a GET "${j_COLLIDE}" afu ${key})
      string(JSON b GET "${j_COSIM}" afu ${key})
      if(NOT a STREQUAL b)
        message(FATAL_ERROR "${file}: afu.${key} ${a} (RTL) != ${b} (cosim)")
      endif()
    endforeach()
    if(NOT pos_COLLIDE STREQUAL pos_COSIM)
      message(FATAL_ERROR "${file}: final positions differ between the RTL and cosim")
    endif()
  endforeach()
  file(WRITE ${WORK}/in.csv "${pairs}0x1.fffffep+127,0,0,1,-0x1.fffffep+127,0,0,1\nnan,0,0,1,0,0,0,1\n0,0,0,0x1p-149,0x1p-149,0,0,0x1p-149\n")
  foreach(exe_dir "COLLIDE;default" "COSIM;cosim")
    list(GET exe_dir 0 exe)
    list(GET exe_dir 1 dir)
    execute_process(COMMAND ${${exe}} pairs --afu ${REPO}/generated/${dir} --dense --link qpi --clock-mhz 200 --in ${WORK}/in.csv
                            --out ${WORK}/${exe}_pairs.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    file(READ ${WORK}/${exe}_pairs.csv pairs_${exe})
  endforeach()
  if(NOT pairs_COLLIDE STREQUAL pairs_COSIM)
    message(FATAL_ERROR "pairs differ:\n--- RTL\n${pairs_COLLIDE}--- cosim\n${pairs_COSIM}")
  endif()
elseif(CHECK STREQUAL "afu_pairs")
  file(WRITE ${WORK}/in.csv "${pairs}")
  foreach(link ideal qpi)
    execute_process(COMMAND ${COLLIDE} pairs --afu ${AFU_DIR} --link ${link} --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    # The clock line: the link's (the target) or, lower, what the Verilog reaches (timing.json).
    expect_match("${err}" "\n  AFU clock [0-9.]+ MHz: (the target(, reached)?|what its cells reach, short of the target [0-9.]+ MHz);")
  endforeach()
  # The baseline of the study below: 200 MHz named, so it does not hang on the Verilog's clock.
  execute_process(COMMAND ${COLLIDE} pairs --afu ${AFU_DIR} --link qpi --clock-mhz 200 --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  # At another clock: the same contacts, more time, the clock named; out of range or without
  # an AFU it is refused, naming the option.
  execute_process(COMMAND ${COLLIDE} pairs --afu ${AFU_DIR} --link qpi --clock-mhz 50 --in ${WORK}/in.csv
                          --out ${WORK}/out50.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err50)
  expect_rc(0)
  expect_match("${err50}" "link qpi at 50 MHz")
  # Slower: a cycle is four times as long, and the link's latencies (in ns) are fewer cycles.
  string(REGEX MATCH "([0-9.]+) us modelled" m "${err50}")
  set(us50 ${CMAKE_MATCH_1})
  string(REGEX MATCH "([0-9.]+) us modelled" m "${err}")
  set(us200 ${CMAKE_MATCH_1})
  if(us50 STREQUAL "" OR us200 STREQUAL "" OR NOT us50 GREATER us200)
    message(FATAL_ERROR "--clock-mhz 50: ${us50} us modelled, not more than ${us200} us at 200 MHz")
  endif()
  file(READ ${WORK}/out50.csv got50)
  execute_process(COMMAND ${COLLIDE} pairs --afu ${AFU_DIR} --clock-mhz 3000 --in ${WORK}/in.csv --out ${WORK}/bad.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz: clock_mhz: 3000 MHz is outside the sane range")
  execute_process(COMMAND ${COLLIDE} pairs --backend simd --clock-mhz 50 --in ${WORK}/in.csv --out ${WORK}/bad.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz applies to the AFU")
  if(EXISTS ${WORK}/bad.csv)
    message(FATAL_ERROR "a refused --clock-mhz wrote ${WORK}/bad.csv")
  endif()
  file(READ ${WORK}/out.csv got)
  if(NOT got50 STREQUAL got)
    message(FATAL_ERROR "--clock-mhz 50 changed the contacts:\n${got50}--- against\n${got}")
  endif()
  # The fp32 answers of the pairs_simd check (coincident, grazing, separated).
  set(want "pair,hit,px,py,pz,nx,ny,nz,depth,flags\n0,1,0x0p+0,0x0p+0,0x0p+0,0x1p+0,0x0p+0,0x0p+0,0x1.8p+1,5\n1,1,0x1.ccccccp+0,0x1.333334p+1,0x0p+0,0x1.333334p-1,0x1.99999ap-1,0x0p+0,0x0p+0,3\n2,0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0\n")
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "contacts.csv differs:\n--- got\n${got}--- want\n${want}")
  endif()
elseif(CHECK STREQUAL "write_full")
  # Every file the CLI writes: a full disk is an error naming the file, never exit 0.
  if(NOT EXISTS /dev/full)
    message(STATUS "no /dev/full on this machine: skipped")
    return()
  endif()
  file(WRITE ${WORK}/in.csv "${pairs}")
  foreach(cmd "pairs;--backend;simd;--in;${WORK}/in.csv;--out"
              "run;${REPO}/scenes/small.json;--steps;2;--out"
              "run;${REPO}/scenes/small.json;--steps;2;--summary"
              "run;${REPO}/scenes/small.json;--steps;2;--positions")
    execute_process(COMMAND ${COLLIDE} ${cmd} /dev/full RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "/dev/full: write failed: No space left on device")
  endforeach()
elseif(CHECK STREQUAL "write_fail_keeps_old")
  # A write that fails half-way (a 1 KiB file-size limit, SIGXFSZ ignored so write() says
  # EFBIG) must leave the old file as it was and no temporary behind.
  set(big "x1,y1,z1,r1,x2,y2,z2,r2\n")
  foreach(k RANGE 200)
    string(APPEND big "${k},0,0,1,${k}.5,0,0,1\n")
  endforeach()
  file(WRITE ${WORK}/in.csv "${big}")
  file(WRITE ${WORK}/out.csv "old\n")
  execute_process(COMMAND sh -c "ulimit -f 2 && trap '' XFSZ && exec \"$0\" pairs --backend simd --in in.csv --out out.csv" ${COLLIDE}
                  WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "out.csv: write failed: File too large")
  file(READ ${WORK}/out.csv got)
  if(NOT got STREQUAL "old\n")
    message(FATAL_ERROR "out.csv was changed by the failed write:\n${got}")
  endif()
  file(GLOB left ${WORK}/.out.csv.tmp.*)
  if(left)
    message(FATAL_ERROR "temporary left behind: ${left}")
  endif()
elseif(CHECK STREQUAL "deep_json")
  # 100,000 levels of nesting in a scene and in a manifest: exit 1 naming the file and the
  # key path (the error path overflowed the stack, SIGSEGV, before); a huge value is clipped.
  string(REPEAT "[" 100000 open)
  string(REPEAT "]" 100000 close)
  file(WRITE ${WORK}/deep.json "{\"steps\": 1, \"dt\": 0.01, \"bodies\": {\"spheres\": ${open}${close}}}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/deep.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "deep.json: scene.bodies.spheres\\[0\\]\\[0\\].*: nested deeper than 64 levels")
  file(MAKE_DIRECTORY ${WORK}/afu)
  file(WRITE ${WORK}/afu/manifest.json "{\"link\": ${open}${close}}")
  execute_process(COMMAND ${COLLIDE} info --afu ${WORK}/afu RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "afu/manifest.json: manifest.link\\[0\\].*: nested deeper than 64 levels")
  string(REPEAT "x" 1000000 big)
  file(WRITE ${WORK}/big.json "{\"steps\": \"${big}\", \"dt\": 0.01, \"bodies\": {}}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/big.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  string(LENGTH "${err}" n)
  if(n GREATER 300)
    message(FATAL_ERROR "a 1 MB value was echoed in ${n} characters")
  endif()
  expect_match("${err}" "scene.steps: expected a positive integer, got \"xxx+\\.\\.\\.")
elseif(CHECK STREQUAL "link_absurd")
  # Absurd link numbers are refused with the key, the value and the range (they were
  # accepted and overflowed a conversion to cycles before).
  foreach(kv "read_latency_ns\": 1e30;read_latency_ns: 1e\\+30 ns is outside the sane range 0..1e\\+06 ns"
             "read_gbps\": 1e-300;read_gbps: 1e-300 GB/s is outside the sane range 0 \\(unlimited\\) or 0.001..10000 GB/s"
             "clock_mhz\": 1e15;clock_mhz: 1e\\+15 MHz is outside the sane range 1..2000 MHz"
             "transaction_overhead_ns\": 1e300;transaction_overhead_ns: 1e\\+300 ns is outside")
    list(GET kv 0 setting)
    list(GET kv 1 want)
    file(WRITE ${WORK}/bad.json "{\"steps\": 1, \"dt\": 0.01, \"link\": {\"type\": \"qpi\", \"${setting}}, \"bodies\": {\"diamond\": {\"hMax\": 2}}}")
    execute_process(COMMAND ${COLLIDE} run ${WORK}/bad.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "scene.link.${want}")
  endforeach()
elseif(CHECK STREQUAL "input_mistakes")
  # Careless inputs get messages that say what is wrong.
  file(MAKE_DIRECTORY ${WORK}/adir)
  execute_process(COMMAND ${COLLIDE} pairs --backend simd --in ${WORK}/adir --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "adir: is a directory, expected a file")
  # A byte-order mark before the header (spreadsheets write one) is accepted.
  string(ASCII 239 187 191 bom)
  file(WRITE ${WORK}/bom.csv "${bom}${pairs}")
  execute_process(COMMAND ${COLLIDE} pairs --backend simd --in ${WORK}/bom.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  # --steps: a readable bound, and a huge value refused, not clamped to 2^63-1.
  foreach(steps 0 99999999999999999999999 1000000001 1e9 -3)
    execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --steps ${steps}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      message(FATAL_ERROR "--steps ${steps} accepted:\n${out}")
    endif()
    expect_match("${err}" "--steps: expected an integer in 1..1000000000, got '?${steps}'?")
  endforeach()
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/small.json --steps 1000000000x
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_match("${err}" "--steps: expected an integer")
  # An unknown subcommand is named.
  execute_process(COMMAND ${COLLIDE} frobnicate RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "unknown subcommand 'frobnicate' \\(expected run, pairs, spheres or info\\)")
  # Manifest errors name the file, a wrong type included.
  file(MAKE_DIRECTORY ${WORK}/afu)
  file(WRITE ${WORK}/afu/manifest.json "{\"link\": {\"format\": 32}}")
  execute_process(COMMAND ${COLLIDE} info --afu ${WORK}/afu RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "afu/manifest.json: link.format: expected a string, got 32")
elseif(CHECK STREQUAL "ode_bad_input")
  # Values that made ODE abort (SIGABRT) are no contact with their flag (docs/host.md, "Bad
  # pairs"): 8 non-finite, 32 a negative radius; a zero radius is computed (a coincident
  # contact, 37 = hit, coincident, 32 outside a scene's range). The good pair after them is
  # computed, and stderr ends with the count of flagged pairs.
  foreach(bad "-1;0;32;outside the host's range" "nan;0;8;non-finite input" "0;1;37;outside the host's range")
    list(GET bad 0 r)
    list(GET bad 1 hit)
    list(GET bad 2 want)
    list(GET bad 3 said)
    file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n0,0,0,${r},0,0,0,2\n0,0,0,1,1,0,0,1\n")
    execute_process(COMMAND ${COLLIDE} pairs --backend ode --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    file(READ ${WORK}/out.csv got)
    expect_match("${got}" "\n0,${hit},[^\n]*,${want}\n1,1,")
    expect_match("${err}" "collide pairs: flagged 1 pair: 1 ${said}[^\n]*\n$")
  endforeach()
  # No finite pair is refused: 1e30 m is computed on every backend, and a value binary16
  # cannot hold flags its pair (8 + 32: it became infinite), not the whole file.
  file(WRITE ${WORK}/in.csv "x1,y1,z1,r1,x2,y2,z2,r2\n1e30,0,0,1e30,-1e30,0,0,1e30\n1e5,0,0,1,0,0,0,1\n0,0,0,1,1,0,0,1\n")
  foreach(backend ode simd64)
    execute_process(COMMAND ${COLLIDE} pairs --backend ${backend} --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    file(READ ${WORK}/out.csv got)
    expect_match("${got}" "\n0,1,0x1p\\+47,[^\n]*,35\n1,0,[^\n]*,0\n2,1,")
  endforeach()
  execute_process(COMMAND ${COLLIDE} pairs --backend model:fp16 --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  file(READ ${WORK}/out.csv got)
  expect_match("${got}" "\n0,0,[^\n]*,40\n1,0,[^\n]*,40\n2,1,")
  expect_match("${err}" "flagged 2 pairs: 2 non-finite input \\(8\\), 2 outside the host's range or the link format \\(32\\)\n$")
  file(WRITE ${WORK}/far.json "{\"steps\": 2, \"dt\": 0.01, \"bodies\": {\"spheres\": [{\"pos\": [1e9, 0, 0], \"r\": 0.1}]}}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/far.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "scene.bodies.spheres\\[0\\].pos: expected \\[x, y, z\\] within \\+-1e6 m")
  # A cloud larger than ODE's hash space holds (it asserted in dSpaceCollide): refused, with the way out.
  file(WRITE ${WORK}/cloud.json "{\"steps\": 1, \"dt\": 0.01, \"backend\": \"simd\", \"bodies\": {\"random_cloud\": {\"count\": 140000, \"seed\": 1, \"min\": [0, 0, 0], \"max\": [200, 200, 200], \"radius\": 0.2}}}")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/cloud.json RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "scene.bodies: 140000 spheres, more than ODE's hash space holds \\(131071[^\n]*\"space\": \"sap\"")
  file(WRITE ${WORK}/fly.json "{\"steps\": 50, \"dt\": 0.01, \"bodies\": {\"spheres\": [{\"pos\": [0, 0, 0], \"r\": 0.5, \"vel\": [1e12, 0, 0]}, {\"pos\": [3, 0, 0], \"r\": 0.5}]}}")
  file(WRITE ${WORK}/steps.csv "old\n")
  execute_process(COMMAND ${COLLIDE} run ${WORK}/fly.json --out ${WORK}/steps.csv RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "step 1: sphere 0 left the sane range")
  file(READ ${WORK}/steps.csv got)
  if(NOT got STREQUAL "old\n")
    message(FATAL_ERROR "steps.csv changed by the failed run:\n${got}")
  endif()
elseif(CHECK STREQUAL "spheres_simd_ode")
  # World mode on both CPU backends: the same contacts (exact values here), i < j sorted, bad
  # spheres once each with j empty; --repeat and --summary.
  file(WRITE ${WORK}/in.csv "x,y,z,r\n0,0,0,1\n0x1.8p+1,0,0,1\n 1.5 ,0,0,1\n\nnan,0,0,1\n0,0,0,-1\n-8,-8,-8,0.1\n-8,-8,-7.75,0.2\n")
  set(zeros "0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0,0x0p+0")
  foreach(backend simd ode)
    execute_process(COMMAND ${COLLIDE} spheres --backend ${backend} --in ${WORK}/in.csv --out ${WORK}/out.csv
                            --repeat 3 --summary ${WORK}/summary.json
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "7 spheres \\(2 bad\\), [0-9]+ candidate pairs, 3 contacts")
    expect_match("${err}" "time \\(fastest of 3\\): broad [0-9.]+ us, narrow [0-9.]+ us")
    file(READ ${WORK}/out.csv got)
    string(REGEX MATCH "\n5,6,[^\n]*\n" row56 "${got}")
    string(REGEX REPLACE "\n5,6,[^\n]*\n" "\n5,6,ROW\n" got "${got}")
    set(want "i,j,px,py,pz,nx,ny,nz,depth,flags\n0,2,0x1.8p-1,0x0p+0,0x0p+0,-0x1p+0,0x0p+0,0x0p+0,0x1p-1,3\n1,2,0x1.2p+1,0x0p+0,0x0p+0,0x1p+0,0x0p+0,0x0p+0,0x1p-1,3\n3,,${zeros},8\n4,,${zeros},32\n5,6,ROW\n")
    if(NOT got STREQUAL want)
      message(FATAL_ERROR "${backend}: contacts.csv differs:\n--- got\n${got}--- want\n${want}")
    endif()
    expect_match("${row56}" "^\n5,6,-0x1p\\+3,-0x1p\\+3,-0x1.f[0-9a-f]*p\\+2,")
    file(READ ${WORK}/summary.json summary)
    string(JSON n GET "${summary}" contacts)
    string(JSON repeat GET "${summary}" repeat)
    string(JSON backendName GET "${summary}" backend)
    if(NOT n EQUAL 3 OR NOT repeat EQUAL 3 OR NOT backendName STREQUAL backend)
      message(FATAL_ERROR "summary.json: ${summary}")
    endif()
    set(row56_${backend} "${row56}")
  endforeach()
  # 0.1 and 7.75 - 8 are not the same in binary32 and binary64: the rows print each format.
  if(row56_simd STREQUAL row56_ode)
    message(FATAL_ERROR "simd and ode printed the same binary32/binary64 row: ${row56_simd}")
  endif()
  foreach(space hash sap)
    execute_process(COMMAND ${COLLIDE} spheres --backend ode --space ${space} --in ${WORK}/in.csv --out ${WORK}/out_${space}.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "broad phase ode ${space}, narrow phase ode \\(binary64\\)")
  endforeach()
  file(READ ${WORK}/out_hash.csv hash)
  file(READ ${WORK}/out_sap.csv sap)
  if(NOT hash STREQUAL sap)
    message(FATAL_ERROR "ode hash and sap differ:\n${hash}\n${sap}")
  endif()
elseif(CHECK STREQUAL "spheres_grid")
  # The tuned grid writes simd's contacts byte for byte at every thread count (bad spheres,
  # touching and coincident pairs among them); --threads is checked and names itself.
  simd_reference_world()
  foreach(threads 1 2 3)
    execute_process(COMMAND ${COLLIDE} spheres --backend grid --threads ${threads} --in ${WORK}/in.csv --out ${WORK}/grid.csv
                            --repeat 2 --summary ${WORK}/summary.json
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "10 spheres \\(2 bad\\), [0-9]+ candidate pairs, [0-9]+ contacts, grid \\(tuned, ${threads} threads?\\)")
    expect_match("${err}" "time \\(fastest of 2\\): broad [0-9.]+ us, narrow [0-9.]+ us, finish [0-9.]+ us")
    expect_simd_contacts(${WORK}/grid.csv "--threads ${threads}")
    file(READ ${WORK}/summary.json summary)
    string(JSON n GET "${summary}" threads)
    string(JSON backendName GET "${summary}" backend)
    if(NOT n EQUAL threads OR NOT backendName STREQUAL "grid")
      message(FATAL_ERROR "summary.json: ${summary}")
    endif()
  endforeach()
  # Default: every hardware thread.
  execute_process(COMMAND ${COLLIDE} spheres --backend grid --in ${WORK}/in.csv --out ${WORK}/grid.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_simd_contacts(${WORK}/grid.csv "default threads")
  foreach(threads 0 -2 abc 1.5 1025 99999999999)
    execute_process(COMMAND ${COLLIDE} spheres --backend grid --threads=${threads} --in ${WORK}/in.csv --out ${WORK}/bad.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      message(FATAL_ERROR "--threads ${threads} accepted:\n${err}")
    endif()
    expect_match("${err}" "--threads: expected a whole number of threads in 1..1024, got '?${threads}'?")
  endforeach()
  foreach(backend simd ode)
    execute_process(COMMAND ${COLLIDE} spheres --backend ${backend} --threads 2 --in ${WORK}/in.csv --out ${WORK}/bad.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc EQUAL 0)
      message(FATAL_ERROR "--threads with ${backend} accepted")
    endif()
    expect_match("${err}" "--threads applies to --backend grid")
  endforeach()
elseif(CHECK STREQUAL "spheres_engines")
  # Bullet's and FCL's broad phases feed the binary32 kernel: simd's contacts byte for byte
  # (bad spheres, touching and coincident pairs among them), with the engine's own narrow
  # phase counted on stderr and in the summary; ODE's quadtree writes ODE sap's contacts. A
  # build without an engine (HAVE_BULLET, HAVE_FCL) says so; a space of another engine is refused.
  simd_reference_world()
  foreach(run "bullet;dbvt;${HAVE_BULLET}" "bullet;sap;${HAVE_BULLET}" "fcl;tree;${HAVE_FCL}" "fcl;sap;${HAVE_FCL}"
              "fcl;hash;${HAVE_FCL}")
    list(GET run 0 backend)
    list(GET run 1 space)
    list(GET run 2 have)
    execute_process(COMMAND ${COLLIDE} spheres --backend ${backend} --space ${space} --in ${WORK}/in.csv
                            --out ${WORK}/${backend}.csv --repeat 2 --summary ${WORK}/summary.json
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT have)
      expect_rc(1)
      expect_match("${err}" "--backend ${backend}: this build has no")
      continue()
    endif()
    expect_rc(0)
    expect_match("${err}" "10 spheres \\(2 bad\\), [0-9]+ candidate pairs, [0-9]+ contacts, broad phase ${backend} ${space} \\(")
    expect_match("${err}" "narrow phase simd \\(binary32\\)")
    expect_match("${err}" "the engine's own narrow phase, [^\n]*: [0-9.]+ us, [0-9]+ contacts \\(0 that binary32 calls no contact, 0 binary32 contacts it misses")
    expect_simd_contacts(${WORK}/${backend}.csv "${backend} ${space}")
    file(READ ${WORK}/summary.json summary)
    string(JSON backendName GET "${summary}" backend)
    string(JSON narrowName GET "${summary}" narrow_phase)
    string(JSON onlyExact GET "${summary}" engine only_exact)
    if(NOT backendName STREQUAL backend OR NOT narrowName STREQUAL "simd" OR NOT onlyExact EQUAL 0)
      message(FATAL_ERROR "summary.json: ${summary}")
    endif()
  endforeach()
  foreach(space sap quadtree)
    execute_process(COMMAND ${COLLIDE} spheres --backend ode --space ${space} --in ${WORK}/in.csv --out ${WORK}/ode_${space}.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "broad phase ode ${space}, narrow phase ode \\(binary64\\)")
  endforeach()
  file(READ ${WORK}/ode_sap.csv sap)
  file(READ ${WORK}/ode_quadtree.csv quad)
  if(NOT sap STREQUAL quad)
    message(FATAL_ERROR "ode sap and quadtree differ:\n${sap}\n${quad}")
  endif()
  foreach(bad "bullet;tree;is no Bullet broad phase" "fcl;dbvt;is no FCL manager" "ode;dbvt;is no ODE space"
              "simd;quadtree;applies to --backend ode, bullet or fcl")
    list(GET bad 0 backend)
    list(GET bad 1 space)
    list(GET bad 2 message)
    execute_process(COMMAND ${COLLIDE} spheres --backend ${backend} --space ${space} --in ${WORK}/in.csv --out ${WORK}/bad.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "--space ${space} ${message}")
  endforeach()
elseif(CHECK STREQUAL "spheres_bad_input")
  # Bad files name the file, the line and the problem; an AFU without world mode (or none) says so.
  foreach(case "x,y,z\n;in.csv:1: expected the header 'x,y,z,r', got 'x,y,z'"
               "x,y,z,r\n0,0,0,1\n1,2,3\n;in.csv:3: expected 4 fields, got 3"
               "x,y,z,r\n0,0,0,1\n1,2,abc,1\n;in.csv:3: z: not a number: 'abc'"
               "x,y,z,r\n1e39,0,0,1\n;in.csv:2: x: '1e39' overflows binary32"
               "EMPTY;in.csv:1: empty input: expected the header 'x,y,z,r'")
    list(GET case 0 text)
    list(GET case 1 want)
    string(REPLACE "\\n" "\n" text "${text}")
    string(REPLACE "EMPTY" "" text "${text}")
    file(WRITE ${WORK}/in.csv "${text}")
    execute_process(COMMAND ${COLLIDE} spheres --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "${want}")
  endforeach()
  file(MAKE_DIRECTORY ${WORK}/adir)
  execute_process(COMMAND ${COLLIDE} spheres --in ${WORK}/adir --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "adir: is a directory, expected a file")
  file(WRITE ${WORK}/in.csv "x,y,z,r\n0,0,0,1\n")
  foreach(args "--backend;rtl" "--afu;${WORK}/adir")
    execute_process(COMMAND ${COLLIDE} spheres ${args} --in ${WORK}/in.csv --out ${WORK}/out.csv
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(2)
    expect_match("${err}" "no world mode|no AFU available")
  endforeach()
  execute_process(COMMAND ${COLLIDE} spheres --backend simd --space hash --in ${WORK}/in.csv --out ${WORK}/out.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--space hash applies to --backend ode")
  if(EXISTS /dev/full)
    execute_process(COMMAND ${COLLIDE} spheres --in ${WORK}/in.csv --out /dev/full
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(1)
    expect_match("${err}" "/dev/full: write failed: No space left on device")
  endif()
elseif(CHECK STREQUAL "run_world_offload")
  # A scene offloading the whole collision: the CPU grid with simd runs it; ode is refused.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box_world.json --steps 2 --summary ${WORK}/s.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "offload world: simd")
  expect_match("${out}" "broad phase .*grid \\+ binary32 kernel\\)'s broad phase, measured")
  file(READ ${WORK}/s.json summary)
  string(JSON offload GET "${summary}" offload)
  if(NOT offload STREQUAL "world")
    message(FATAL_ERROR "summary offload: ${offload}")
  endif()
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box_world.json --steps 2 --backend ode
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "collision.offload \"world\" needs backend simd or rtl, not ode")
elseif(CHECK STREQUAL "afu_run_world")
  # The same scene on the AFU's world mode: one step, its modelled time split; evaluating
  # every cycle (--no-skip) prints the same AFU line (time to the nanosecond, per-collision costs): skipping is exact.
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box_world.json --backend rtl --steps 1
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${out}" "contacts     : 2217 sphere/sphere")
  expect_match("${out}" "  broad phase +[0-9.]+ us +[0-9.]+ % +\\(world mode")
  string(REGEX MATCH "AFU \\(modelled[^\n]*" skipped "${out}")
  string(REGEX MATCH "[0-9]+ skipped exactly" nskipped "${out}")
  if(nskipped STREQUAL "0 skipped exactly")
    message(FATAL_ERROR "no idle cycle was skipped, so the comparison below tests nothing:\n${out}")
  endif()
  execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box_world.json --backend rtl --steps 1 --no-skip
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  string(REGEX MATCH "AFU \\(modelled[^\n]*" stepped "${out}")
  expect_match("${out}" " 0 skipped exactly")
  if(NOT skipped STREQUAL stepped OR skipped STREQUAL "")
    message(FATAL_ERROR "skipping changed the AFU's time:\n  skipped: ${skipped}\n  stepped: ${stepped}")
  endif()
  # At a quarter of the link's clock (--clock-mhz over the scene's link): the same contacts, the
  # clock in the header and the summary, and the modelled time nearly four times as long (the
  # link's latencies in ns are fewer cycles there, so the cycles may be fewer, never more).
  foreach(clock 200 50)
    execute_process(COMMAND ${COLLIDE} run ${REPO}/scenes/pile_box_world.json --backend rtl --link ideal --steps 1
                            --clock-mhz ${clock} --summary ${WORK}/at${clock}.json
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out${clock} ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${out${clock}}" "link ideal, AFU [a-z0-9-]+ at ${clock} MHz")
    expect_match("${out${clock}}" "contacts     : 2217 sphere/sphere")
    file(READ ${WORK}/at${clock}.json summary${clock})
    string(JSON mhz${clock} GET "${summary${clock}}" afu clock_mhz)
    string(JSON cyc${clock} GET "${summary${clock}}" afu cycles_total)
    string(JSON ns${clock} GET "${summary${clock}}" afu modelled_ns)
  endforeach()
  string(REGEX REPLACE "\\..*" "" low "${ns200}")  # its integer part: math() takes integers
  math(EXPR lo "${low} * 35 / 10")
  math(EXPR hi "${low} * 4 + 4")
  if(NOT mhz50 EQUAL 50 OR NOT mhz200 EQUAL 200 OR cyc50 GREATER cyc200 OR ns50 LESS lo OR ns50 GREATER hi)
    message(FATAL_ERROR "run --clock-mhz 50: clock ${mhz50} (${mhz200}), ${cyc50} AFU cycles (${cyc200}), "
                        "${ns50} ns against ${ns200} at 200 MHz (want ${lo}..${hi})")
  endif()
elseif(CHECK STREQUAL "spheres_afu_world")
  # World mode on the AFU: the same contacts, flags and bad-sphere rows as the CPU grid with
  # the binary32 kernel, byte for byte, over two links; the summary names the AFU's run.
  set(in ${REPO}/test/scenes/world_mix.csv)
  execute_process(COMMAND ${COLLIDE} spheres --backend simd --in ${in} --out ${WORK}/simd.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  foreach(link ideal qpi)
    execute_process(COMMAND ${COLLIDE} spheres --afu ${AFU_DIR} --link ${link} --in ${in} --out ${WORK}/afu_${link}.csv
                            --summary ${WORK}/afu_${link}.json
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    expect_rc(0)
    expect_match("${err}" "on the AFU \\(world mode")
    file(READ ${WORK}/simd.csv want)
    file(READ ${WORK}/afu_${link}.csv got)
    if(NOT got STREQUAL want)
      message(FATAL_ERROR "spheres --afu (${link}) differs from --backend simd; see ${WORK}")
    endif()
    file(READ ${WORK}/afu_${link}.json summary)
    string(JSON contacts GET "${summary}" contacts)
    string(JSON cycles GET "${summary}" afu cycles_broad)
    if(contacts LESS 500 OR cycles EQUAL 0)
      message(FATAL_ERROR "summary: ${contacts} contacts, ${cycles} broad-phase cycles:\n${summary}")
    endif()
    # One run here: per_run holds it, with the call's broad-phase cycles and every sphere.
    string(JSON runs LENGTH "${summary}" afu per_run)
    string(JSON run_cycles GET "${summary}" afu per_run 0 cycles_broad)
    string(JSON run_spheres GET "${summary}" afu per_run 0 spheres)
    string(JSON spheres GET "${summary}" spheres)
    string(JSON bad GET "${summary}" bad_spheres)
    math(EXPR sent "${spheres} - ${bad}")
    if(NOT runs EQUAL 1 OR NOT run_cycles EQUAL cycles OR NOT run_spheres EQUAL sent)
      message(FATAL_ERROR "summary per_run: ${runs} runs, ${run_cycles} cycles of ${cycles}, ${run_spheres} spheres of ${sent}:\n${summary}")
    endif()
  endforeach()
  # At half the ideal link's clock: the same contacts and broad-phase cycles, the clock in the
  # summary, and nearly twice the time (the link's 5 ns latencies are fewer cycles there).
  execute_process(COMMAND ${COLLIDE} spheres --afu ${AFU_DIR} --link ideal --clock-mhz 100 --in ${in}
                          --out ${WORK}/afu_100.csv --summary ${WORK}/afu_100.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  expect_match("${err}" "link ideal at 100 MHz")
  file(READ ${WORK}/afu_100.csv got)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "spheres --afu --clock-mhz 100 differs from --backend simd; see ${WORK}")
  endif()
  # Without --clock-mhz the time used the lower of the link's 200 MHz and the Verilog's reach.
  file(READ ${WORK}/afu_ideal.json atDefault)
  string(JSON used GET "${atDefault}" afu clock used_mhz)
  string(JSON reached TYPE "${atDefault}" afu clock reached)
  if(reached STREQUAL "NULL")
    set(want_used 200)
  else()
    string(JSON want_used GET "${atDefault}" afu clock reached proxy_mhz)
    if(want_used GREATER 200)
      set(want_used 200)
    endif()
  endif()
  if(NOT used EQUAL want_used)
    message(FATAL_ERROR "spheres --afu without --clock-mhz used ${used} MHz, not ${want_used}:\n${atDefault}")
  endif()
  execute_process(COMMAND ${COLLIDE} spheres --afu ${AFU_DIR} --link ideal --clock-mhz 200 --in ${in}
                          --out ${WORK}/afu_200.csv --summary ${WORK}/afu_200.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(0)
  file(READ ${WORK}/afu_200.json at200)
  file(READ ${WORK}/afu_100.json at100)
  string(JSON clock GET "${at100}" afu clock_mhz)
  string(JSON clock200 GET "${at200}" afu clock_mhz)
  string(JSON ns200 GET "${at200}" afu modelled_ns)
  string(JSON ns100 GET "${at100}" afu modelled_ns)
  string(JSON cyc200 GET "${at200}" afu cycles_broad)
  string(JSON cyc100 GET "${at100}" afu cycles_broad)
  string(REGEX REPLACE "\\..*" "" low "${ns200}")  # its integer part: math() takes integers
  math(EXPR lo "${low} * 18 / 10")
  math(EXPR hi "${low} * 2 + 2")
  if(NOT clock EQUAL 100 OR NOT clock200 EQUAL 200 OR NOT cyc100 EQUAL cyc200 OR ns100 LESS lo OR ns100 GREATER hi)
    message(FATAL_ERROR "--clock-mhz 100: clock ${clock} (${clock200} without), broad phase ${cyc100} cycles "
                        "(${cyc200}), ${ns100} ns against ${ns200} at 200 MHz (want ${lo}..${hi})")
  endif()
  # Out of the link's clock range, or on a CPU backend: refused, naming the option.
  execute_process(COMMAND ${COLLIDE} spheres --afu ${AFU_DIR} --clock-mhz 5000 --in ${in} --out ${WORK}/bad.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz: clock_mhz: 5000 MHz is outside the sane range")
  # 0 is a clock like any other, out of range: not "the preset's"
  execute_process(COMMAND ${COLLIDE} spheres --afu ${AFU_DIR} --clock-mhz 0 --in ${in} --out ${WORK}/bad.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz: clock_mhz: 0 MHz is outside the sane range")
  execute_process(COMMAND ${COLLIDE} spheres --backend simd --clock-mhz 50 --in ${in} --out ${WORK}/bad.csv
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  expect_rc(1)
  expect_match("${err}" "--clock-mhz applies to the AFU")
else()
  message(FATAL_ERROR "unknown CHECK ${CHECK}")
endif()
