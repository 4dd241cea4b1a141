# SPDX-License-Identifier: MIT
# SC_BUILD_PYTHON: the pybind11 module `smartcollision`, on by default when pybind11
# and a Python 3 that imports numpy are found.

# The first python3 that imports numpy: a version manager's python3 first on PATH
# may lack the Debian packages, /usr/bin/python3 has them (scripts/setup.sh).
function(sc_find_python_with_numpy out)
  find_program(SC_PATH_PYTHON3 python3)
  foreach(py IN ITEMS ${SC_PATH_PYTHON3} /usr/bin/python3)
    if(py AND EXISTS "${py}")
      execute_process(COMMAND "${py}" -c "import numpy" RESULT_VARIABLE rc
                      OUTPUT_QUIET ERROR_QUIET)
      if(rc EQUAL 0)
        set(${out} "${py}" PARENT_SCOPE)
        return()
      endif()
    endif()
  endforeach()
  set(${out} "" PARENT_SCOPE)
endfunction()

if(NOT DEFINED SC_BUILD_PYTHON OR SC_BUILD_PYTHON)
  if(NOT Python3_EXECUTABLE)
    sc_find_python_with_numpy(sc_python)
    if(sc_python)
      set(Python3_EXECUTABLE "${sc_python}" CACHE FILEPATH "Python 3 interpreter of the module")
    endif()
  endif()
  if(Python3_EXECUTABLE)
    find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
    set(PYBIND11_FINDPYTHON ON)
    find_package(pybind11 CONFIG QUIET)
  endif()
endif()

set(sc_python_default OFF)
if(pybind11_FOUND AND Python3_FOUND)
  set(sc_python_default ON)
endif()
option(SC_BUILD_PYTHON "Build the Python module (pybind11, numpy)" ${sc_python_default})
if(SC_BUILD_PYTHON AND NOT (pybind11_FOUND AND Python3_FOUND))
  message(FATAL_ERROR "SC_BUILD_PYTHON needs pybind11 and a Python 3 with numpy "
                      "(scripts/setup.sh installs them; or set Python3_EXECUTABLE)")
endif()
