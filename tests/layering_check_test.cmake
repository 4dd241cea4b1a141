# SPDX-License-Identifier: MIT
# The layering check itself: it passes on a tree whose includes go downwards and
# fails, naming the violation, on trees with an upward include through a public
# header, an upward include from a source, and a public header of no layer.
# CHECK is layering_check.cmake, FIXTURES the folder of the small trees.
function(run_check tree expect_failure pattern)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${FIXTURES}/${tree} -P ${CHECK}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(output "${out}${err}")
  if(expect_failure AND rc EQUAL 0)
    message(FATAL_ERROR "${tree}: the check passed; expected a failure:\n${output}")
  elseif(NOT expect_failure AND NOT rc EQUAL 0)
    message(FATAL_ERROR "${tree}: the check failed; expected a pass:\n${output}")
  elseif(NOT output MATCHES "${pattern}")
    message(FATAL_ERROR "${tree}: output does not name '${pattern}':\n${output}")
  endif()
endfunction()

run_check(clean FALSE "layering ok")
run_check(upward_public TRUE
          "smartcollision/mesh.h: public header of layer 'geometry' includes higher layer 'preprocess'")
run_check(upward_source TRUE
          "mesh_validation.h: source of layer 'geometry' includes higher layer 'preprocess'")
run_check(unassigned TRUE "smartcollision/extra.h: public header belongs to no layer")
message(STATUS "layering check ok on every fixture")
