# The interpreter that runs the Python package's tests (ctest python_package): one that imports
# numpy and pytest (Debian's python3-numpy and python3-pytest).
#
# hesai_python_with_numpy_pytest(<out-var>) sets <out-var> to
# - HESAI_PYTHON, when set (-DHESAI_PYTHON=/path/to/python3), if it imports both;
# - else the first of Python3_EXECUTABLE (find_package(Python3): the first python3 on PATH, which
#   may be a pyenv shim or a virtual environment without them) and HESAI_PYTHON_FALLBACK
#   (/usr/bin/python3, Debian's, where apt-get installs them) that imports both.
# When none does, configuring stops (FATAL_ERROR) with the interpreters tried, what each said, and
# the fix: the tests would otherwise fail one by one, or not run, long after the build.
# tests/ci/test_python_choice.sh checks it with a python3 lacking both first on PATH.
set(HESAI_PYTHON "" CACHE FILEPATH "The Python 3 for the Python package's tests (numpy, pytest); empty: chosen")
set(HESAI_PYTHON_FALLBACK /usr/bin/python3 CACHE FILEPATH
    "The interpreter tried after Python3_EXECUTABLE for the Python package's tests (numpy, pytest)")

function(hesai_python_with_numpy_pytest out)
  if(HESAI_PYTHON)
    set(candidates ${HESAI_PYTHON})
  else()
    set(candidates ${Python3_EXECUTABLE} ${HESAI_PYTHON_FALLBACK})
    list(REMOVE_DUPLICATES candidates)
  endif()
  set(tried "")
  foreach(candidate IN LISTS candidates)
    execute_process(COMMAND ${candidate} -c "import numpy, pytest"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE said ERROR_VARIABLE said)
    if(rc EQUAL 0)
      set(${out} ${candidate} PARENT_SCOPE)
      return()
    endif()
    # The last line of what it said (ModuleNotFoundError: No module named 'numpy'), or why it did
    # not run at all.
    string(STRIP "${said}" said)
    string(REGEX REPLACE "^.*\n" "" said "${said}")
    if(said STREQUAL "")
      set(said "${rc}")
    endif()
    string(APPEND tried "\n  ${candidate}: ${said}")
  endforeach()
  if(HESAI_PYTHON)
    set(fix "install them for HESAI_PYTHON, or configure with another -DHESAI_PYTHON=/path/to/python3 that has them")
  else()
    string(CONCAT fix "apt-get install python3-numpy python3-pytest (for ${HESAI_PYTHON_FALLBACK}), "
                  "or configure with -DHESAI_PYTHON=/path/to/python3 naming an interpreter that has them")
  endif()
  message(FATAL_ERROR "The Python package's tests (ctest python_package) need a Python 3 with numpy and "
                      "pytest; none of the interpreters tried imports both:${tried}\nFix: ${fix}.")
endfunction()
