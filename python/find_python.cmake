# SPDX-License-Identifier: GPL-3.0-or-later
# Finds Python 3 and pybind11 for the bindings (python/); included by the top-level CMakeLists.txt
# before the MORPHEX_PYTHON option, whose default is MORPHEX_PYTHON_AVAILABLE.
#
# The first python3 on PATH may be a pyenv or virtualenv interpreter without numpy and pytest
# (which the module's tests need) while the system's has them from Debian packages: unless the
# user chose one with -DPython3_EXECUTABLE, take the first candidate that imports both.
set(MORPHEX_PYTHON_AVAILABLE OFF)
if(NOT DEFINED Python3_EXECUTABLE)
  find_program(_morphex_path_python NAMES python3 NO_CACHE)
  foreach(_candidate ${_morphex_path_python} /usr/bin/python3)
    if(EXISTS "${_candidate}")
      execute_process(COMMAND "${_candidate}" -c "import numpy, pytest"
                      RESULT_VARIABLE _morphex_rc OUTPUT_QUIET ERROR_QUIET)
      if(_morphex_rc EQUAL 0)
        set(Python3_EXECUTABLE "${_candidate}" CACHE FILEPATH "Python 3 for the morphex module")
        break()
      endif()
    endif()
  endforeach()
endif()
find_package(Python3 3.7 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  # pybind11 then uses the Python3 found above instead of searching again.
  set(PYBIND11_FINDPYTHON ON)
  find_package(pybind11 2.6 CONFIG QUIET)
  if(pybind11_FOUND)
    set(MORPHEX_PYTHON_AVAILABLE ON)
  endif()
endif()
