# SPDX-License-Identifier: MIT
# Runs the stacking demo headless under xvfb-run for a few seconds, then checks that
# it wrote its JSON metrics and a PNG that is not blank: a uniform 800x600 frame
# compresses to about 2.7 KB, the rendered tower to about 7 KB.
include(${CMAKE_CURRENT_LIST_DIR}/../common/headless.cmake)
sc_run_headless(stacking json --seconds 3)
if(NOT json MATCHES "\"top_drift_m\"")
  message(FATAL_ERROR "no metrics in stacking.json:\n${json}")
endif()
sc_check_png(${OUT_DIR}/stacking.png 4500 size)
message(STATUS "stacking.png: ${size} bytes")
