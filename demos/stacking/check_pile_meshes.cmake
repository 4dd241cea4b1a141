# SPDX-License-Identifier: MIT
# The pile scene with the user's meshes (--scene pile --mesh ...): CGAL's cow, camel
# and elephant dropped into the box at 60 Hz, headless; the run must stay finite and
# write its metrics and a PNG that is not blank.
include(${CMAKE_CURRENT_LIST_DIR}/../common/headless.cmake)
sc_run_headless(pile_meshes json --scene pile --hz 60 --seconds 2 --mesh ${MESH_DIR}/cow.off
                --mesh ${MESH_DIR}/camel.off --mesh ${MESH_DIR}/elephant.off)
set(failures "")
if(NOT json MATCHES "\"top_drift_m\"")
  string(APPEND failures "no metrics in pile_meshes.json\n")
endif()
if(NOT json MATCHES "\"non_finite_steps\": 0[,\n ]")
  string(APPEND failures "non-finite steps\n")
endif()
sc_check_results(pile_meshes "${json}" "${failures}" size)
message(STATUS "pile_meshes.png: ${size} bytes")
