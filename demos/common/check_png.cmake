# SPDX-License-Identifier: MIT
# Shared by the demos' headless checks (cmake -P): a PNG that is not blank.
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
