# SPDX-License-Identifier: MIT
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(f include/sc.h include/smartcollision/scene.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
set(flags "")
if(SANITIZE)
  set(flags "-fsanitize=address,undefined")
endif()
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX}
    "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=${flags}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
if(EXISTS ${prefix}/include/smartcollision/bullet/bullet.h)
  run(${WORK_DIR}/build/consumer_bullet)
  # Without Bullet (pkg-config finds none) the core alone is still found and linked;
  # requiring the plugin's component says what is missing.
  file(MAKE_DIRECTORY ${WORK_DIR}/no_pkgconfig)
  set(no_bullet ${CMAKE_COMMAND} -E env PKG_CONFIG_LIBDIR=${WORK_DIR}/no_pkgconfig
      PKG_CONFIG_PATH=${WORK_DIR}/no_pkgconfig)
  run(${no_bullet} ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/build_core -G ${GENERATOR}
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_CXX_COMPILER=${CXX}
      "-DCMAKE_CXX_FLAGS=${flags}" "-DCMAKE_EXE_LINKER_FLAGS=${flags}")
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/build_core)
  run(${WORK_DIR}/build_core/consumer)
  if(EXISTS ${WORK_DIR}/build_core/consumer_bullet)
    message(FATAL_ERROR "SmartCollision::sc_bullet defined without Bullet")
  endif()
  execute_process(COMMAND ${no_bullet} ${CMAKE_COMMAND} -S ${CONSUMER_DIR}
                          -B ${WORK_DIR}/build_required -G ${GENERATOR}
                          -DCMAKE_PREFIX_PATH=${prefix} -DSC_REQUIRE_BULLET=ON
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "needs Bullet")
    message(FATAL_ERROR "COMPONENTS bullet without Bullet: rc ${rc}\n${out}\n${err}")
  endif()
endif()
