# SPDX-License-Identifier: MIT
# Installs BUILD_DIR into WORK_DIR/prefix and runs the installed programs (HAVE_*)
# from WORK_DIR/elsewhere with LD_LIBRARY_PATH unset: they must find libsc through
# their RUNPATH and their data under share/smartcollision/.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(elsewhere ${WORK_DIR}/elsewhere)
file(MAKE_DIRECTORY ${elsewhere})

function(run)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH ${ARGN}
                  WORKING_DIRECTORY ${elsewhere} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 240)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  string(LENGTH "${out}" n)
  message(STATUS "ok: ${ARGN} (${n} bytes of output)")
endfunction()

function(require path)
  if(NOT EXISTS ${path})
    message(FATAL_ERROR "not installed or not written: ${path}")
  endif()
endfunction()

execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${err}")
endif()
set(bin ${prefix}/bin)
set(data ${prefix}/share/smartcollision)

if(HAVE_TOOL)
  run(${bin}/sc-preprocess ${MESH} -o ${elsewhere}/l_prism.bvh)
  require(${elsewhere}/l_prism.bvh)
endif()
if(HAVE_HELLO)
  run(${bin}/hello_smartcollision --check)
endif()
if(NOT XVFB_RUN)
  message(STATUS "xvfb-run not found: the viewer demos are not run")
  return()
endif()
# Each headless run is short: it shows the program starts and finds its data.
if(HAVE_STACKING)
  require(${data}/meshes/knot1.off)
  run(${XVFB_RUN} -a ${bin}/stacking --scene pile --headless --seconds 0.5
      --json stacking.json)
  require(${elsewhere}/stacking.json)
endif()
if(HAVE_HAPTIC)
  # The scripts are named without a folder: only the installed copies can match.
  require(${data}/scripts/peg_insertion.txt)
  require(${data}/meshes/bunny00.off)
  run(${XVFB_RUN} -a ${bin}/haptic_coupling --scene peg --device script:peg_insertion.txt
      --headless --lockstep --seconds 0.5 --json peg.json)
  run(${XVFB_RUN} -a ${bin}/haptic_coupling --scene cavity --device script:cavity_push.txt
      --headless --lockstep --seconds 0.5 --json cavity.json)
  require(${elsewhere}/cavity.json)
endif()
if(HAVE_GROUPS)
  run(${XVFB_RUN} -a ${bin}/multiple_groups --headless --seconds 0.5 --json groups.json)
  require(${elsewhere}/groups.json)
endif()
