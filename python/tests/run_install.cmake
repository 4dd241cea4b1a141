# SPDX-License-Identifier: MIT
# Installs the build tree into a scratch prefix and runs README.md's
# `python3 -c "import smartcollision ..."` line against it with only PYTHONPATH set:
# the installed module must find the installed libsc.so by itself.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed: ${err}")
endif()

file(READ ${README} readme)
string(REGEX MATCH "\npython3 -c \"import smartcollision[^\n]*" lines "${readme}")
if(NOT lines)
  message(FATAL_ERROR "README.md must have a line starting with: python3 -c \"import smartcollision")
endif()
# The line's python3 is the interpreter the build is for (Python3_EXECUTABLE).
string(REGEX REPLACE "^\npython3 " "\"${PYTHON}\" " line "${lines}")
string(APPEND line " && \"${PYTHON}\" -c \"import smartcollision; print(smartcollision.__file__)\"")
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH
                        PYTHONPATH=${prefix}/${INSTALL_DIR} sh -c "${line}"
                WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "README line failed (${rc}):\n${line}\n${out}\n${err}")
endif()
if(NOT out MATCHES "${prefix}/${INSTALL_DIR}/smartcollision/__init__.py")
  message(FATAL_ERROR "imported smartcollision from elsewhere than the prefix:\n${out}")
endif()
message(STATUS "${out}")
