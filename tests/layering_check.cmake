# SPDX-License-Identifier: MIT
# Fails when a core file includes a higher layer (geometry <- preprocess <- query
# <- penetration <- scene <- api), when core includes Bullet, when code outside
# core reaches into core/src, or when support/ (shared by tests, demos and bench)
# includes one of its users' headers or the Bullet plugin's.
set(layers geometry preprocess query penetration scene api)
set(errors "")
list(LENGTH layers n)
math(EXPR last "${n} - 1")
foreach(i RANGE ${last})
  list(GET layers ${i} layer)
  file(GLOB_RECURSE files ${SOURCE_DIR}/core/src/${layer}/*.h ${SOURCE_DIR}/core/src/${layer}/*.cpp)
  foreach(f IN LISTS files)
    file(STRINGS ${f} includes REGEX "^#include \"")
    foreach(line IN LISTS includes)
      if(line MATCHES "^#include \"([a-z_]+)/")
        set(dir ${CMAKE_MATCH_1})
        list(FIND layers ${dir} j)
        if(j GREATER i)
          string(APPEND errors "${f}: layer '${layer}' includes higher layer '${dir}': ${line}\n")
        endif()
      endif()
    endforeach()
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
forbid(bullet_plugin demos bench python support tests/conformance tests/scene tests/install
       REGEX "^#include \"(geometry|preprocess|query|penetration|scene|api)/"
       WHAT "reaches into core internals")
forbid(support REGEX "^#include [<\"](\\.\\./|support/|common/|smartcollision/bullet/)"
       WHAT "support includes a user's or the plugin's header")
if(errors)
  message(FATAL_ERROR "layering violations:\n${errors}")
endif()
message(STATUS "layering ok")
