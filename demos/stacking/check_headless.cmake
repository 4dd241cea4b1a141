# SPDX-License-Identifier: MIT
# Runs the stacking demo headless under xvfb-run for a few seconds, then checks that
# it wrote its JSON metrics and a PNG that is not blank: a uniform 800x600 frame
# compresses to about 2.7 KB, the rendered tower to about 7 KB.
include(${CMAKE_CURRENT_LIST_DIR}/../common/check_png.cmake)
file(REMOVE_RECURSE ${OUT_DIR})
file(MAKE_DIRECTORY ${OUT_DIR})
execute_process(COMMAND ${XVFB_RUN} -a ${DEMO} --headless --seconds 3
                        --png ${OUT_DIR}/stacking.png --json ${OUT_DIR}/stacking.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message(STATUS "${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "stacking --headless failed (${rc}):\n${err}")
endif()
file(READ ${OUT_DIR}/stacking.json json)
if(NOT json MATCHES "\"top_drift_m\"")
  message(FATAL_ERROR "no metrics in stacking.json:\n${json}")
endif()
sc_check_png(${OUT_DIR}/stacking.png 4500 size)
message(STATUS "stacking.png: ${size} bytes")
