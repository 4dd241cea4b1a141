# SPDX-License-Identifier: MIT
# Shared by the demos' headless checks (cmake -P): the headless run and a PNG that is
# not blank.
#
# sc_run_headless(NAME JSON_VAR ARGS...): runs DEMO under XVFB_RUN with --headless,
# ARGS, --png OUT_DIR/NAME.png and --json OUT_DIR/NAME.json in a fresh OUT_DIR;
# fails with the demo's stderr on a non-zero exit, else sets JSON_VAR to the JSON.
function(sc_run_headless name json_var)
  file(REMOVE_RECURSE ${OUT_DIR})
  file(MAKE_DIRECTORY ${OUT_DIR})
  execute_process(COMMAND ${XVFB_RUN} -a ${DEMO} --headless ${ARGN} --png ${OUT_DIR}/${name}.png
                          --json ${OUT_DIR}/${name}.json
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} --headless failed (${rc}):\n${err}")
  endif()
  file(READ ${OUT_DIR}/${name}.json json)
  set(${json_var} "${json}" PARENT_SCOPE)
endfunction()

# sc_check_results(NAME JSON FAILURES SIZE_VAR): fails with FAILURES (the checks
# that did not hold, if any) and JSON; else checks OUT_DIR/NAME.png as sc_check_png
# does (4500 bytes at least) and sets SIZE_VAR to its size.
function(sc_check_results name json failures size_var)
  if(failures)
    message(FATAL_ERROR "${failures}\n${json}")
  endif()
  sc_check_png(${OUT_DIR}/${name}.png 4500 size)
  set(${size_var} ${size} PARENT_SCOPE)
endfunction()

# sc_check_png(PATH MIN_BYTES SIZE_VAR): fails unless PATH starts with the PNG
# signature and has at least MIN_BYTES (a uniform 800x600 frame compresses to about
# 2.7 KB); sets SIZE_VAR to its size.
function(sc_check_png path min_bytes size_var)
  get_filename_component(name ${path} NAME)
  if(NOT EXISTS ${path})
    message(FATAL_ERROR "${name} was not written")
  endif()
  file(READ ${path} head LIMIT 8 HEX)
  if(NOT head STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${name} is not a PNG (${head})")
  endif()
  file(SIZE ${path} size)
  if(size LESS ${min_bytes})
    message(FATAL_ERROR "${name} looks blank: ${size} bytes")
  endif()
  set(${size_var} ${size} PARENT_SCOPE)
endfunction()
