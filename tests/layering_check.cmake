# SPDX-License-Identifier: MIT
# Fails when a core file includes a higher layer (geometry <- preprocess <- query
# <- penetration <- scene <- api), directly or through a public header (each public
# header belongs to a layer and includes only its own layer's and lower ones), when
# core includes Bullet, when code outside core reaches into core/src, when the
# collision plugin includes haptics (sc_haptics, haptics/), or when
# support/ (shared by tests, demos and bench) includes one of its users' headers or
# the Bullet plugin's. SOURCE_DIR is the tree checked (tests/layering_check_test.cmake
# runs it on small trees with violations).
set(layers geometry preprocess query penetration scene api)
set(errors "")
list(LENGTH layers n)
math(EXPR last "${n} - 1")
# The layer of each public header (core/include/<name>).
set(public_geometry smartcollision/export.h smartcollision/types.h smartcollision/mesh.h
    smartcollision/placement.h)
set(public_preprocess smartcollision/model.h)
set(public_query smartcollision/group.h)
set(public_penetration smartcollision/pair_settings.h smartcollision/pair_tracker.h)
set(public_scene smartcollision/settings.h smartcollision/collision.h smartcollision/scene.h
    smartcollision/smartcollision.h)
set(public_api sc.h)

# layer_of(<var> <include>): the index of the layer a core/src directory or a
# public header belongs to, -1 when it is neither (a system or third-party header).
function(layer_of var include)
  set(index -1)
  foreach(j RANGE ${last})
    list(GET layers ${j} layer)
    string(REGEX MATCH "^${layer}/" dir "${include}")
    list(FIND public_${layer} "${include}" k)
    if(dir OR k GREATER -1)
      set(index ${j})
    endif()
  endforeach()
  set(${var} ${index} PARENT_SCOPE)
endfunction()

# check_includes(<file> <layer index> <what>): every include of a higher layer, and
# every smartcollision/ header that belongs to no layer, is an error.
function(check_includes f i what)
  list(GET layers ${i} layer)
  file(STRINGS ${f} lines REGEX "^#include [<\"]")
  foreach(line IN LISTS lines)
    if(NOT line MATCHES "^#include [<\"]([^>\"]+)[>\"]")
      continue()
    endif()
    set(include ${CMAKE_MATCH_1})
    layer_of(j ${include})
    if(j GREATER i)
      list(GET layers ${j} higher)
      string(APPEND errors "${f}: ${what} of layer '${layer}' includes higher layer '${higher}': ${line}\n")
    elseif(j EQUAL -1 AND include MATCHES "^smartcollision/[^/]+$")
      string(APPEND errors "${f}: public header belongs to no layer: ${line}\n")
    endif()
  endforeach()
  set(errors "${errors}" PARENT_SCOPE)
endfunction()

file(GLOB public_files RELATIVE ${SOURCE_DIR}/core/include ${SOURCE_DIR}/core/include/*.h
     ${SOURCE_DIR}/core/include/smartcollision/*.h)
foreach(header IN LISTS public_files)
  layer_of(i ${header})
  if(i EQUAL -1)
    string(APPEND errors "core/include/${header}: public header belongs to no layer\n")
  else()
    check_includes(${SOURCE_DIR}/core/include/${header} ${i} "public header")
  endif()
endforeach()
foreach(i RANGE ${last})
  list(GET layers ${i} layer)
  file(GLOB_RECURSE files ${SOURCE_DIR}/core/src/${layer}/*.h ${SOURCE_DIR}/core/src/${layer}/*.cpp)
  foreach(f IN LISTS files)
    check_includes(${f} ${i} "source")
  endforeach()
endforeach()
# forbid(<dir>... REGEX <include regex> WHAT <message>): every .h/.cpp under the
# directories whose includes match the regex is an error.
function(forbid)
  cmake_parse_arguments(arg "" "REGEX;WHAT" "" ${ARGN})
  foreach(dir IN LISTS arg_UNPARSED_ARGUMENTS)
    file(GLOB_RECURSE files ${SOURCE_DIR}/${dir}/*.h ${SOURCE_DIR}/${dir}/*.cpp)
    foreach(f IN LISTS files)
      file(STRINGS ${f} found REGEX "${arg_REGEX}")
      if(found)
        string(APPEND errors "${f}: ${arg_WHAT}: ${found}\n")
      endif()
    endforeach()
  endforeach()
  set(errors "${errors}" PARENT_SCOPE)
endfunction()
forbid(core REGEX "^#include [<\"](btBullet|BulletDynamics|BulletCollision)"
       WHAT "core includes Bullet")
forbid(bullet_plugin haptics demos bench python support tests/conformance tests/scene tests/install
       REGEX "^#include \"(geometry|preprocess|query|penetration|scene|api)/"
       WHAT "reaches into core internals")
forbid(bullet_plugin REGEX "^#include [<\"]smartcollision/haptics/"
       WHAT "the collision plugin includes haptics")
forbid(support REGEX "^#include [<\"](\\.\\./|support/|common/|smartcollision/bullet/)"
       WHAT "support includes a user's or the plugin's header")
if(errors)
  message(NOTICE "${errors}")  # verbatim, one violation a line
  message(FATAL_ERROR "layering violations (listed above)")
endif()
message(STATUS "layering ok")
