# SM2_PYTHON: the Python module sm2emu (python/, docs/python.md), built with pybind11.
# On by default where pybind11 and a Python with its development headers are found, and the
# build is not instrumented (a sanitizer or fuzzer runtime cannot load into an uninstrumented
# python3). The interpreter is Debian's /usr/bin/python3 when it exists, whatever python3 comes
# first in PATH (a pyenv or venv one has not Debian's numpy and pytest); pass
# -DPython3_EXECUTABLE=... for another. The tests run pytest with that same interpreter.
set(sm2_python_default OFF)
if(NOT SM2_SANITIZE AND NOT SM2_FUZZ)
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python of the sm2emu module and its tests")
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
  if(Python3_FOUND)
    find_package(pybind11 CONFIG QUIET)  # after Python3: pybind11 then uses FindPython3's
  endif()
  if(Python3_FOUND AND pybind11_FOUND)
    set(sm2_python_default ON)
  endif()
endif()
option(SM2_PYTHON "Build the Python module sm2emu (needs pybind11 and Python 3 headers)" ${sm2_python_default})
if(SM2_PYTHON)
  if(NOT Python3_FOUND)
    find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
  endif()
  if(NOT pybind11_FOUND)
    find_package(pybind11 CONFIG REQUIRED)
  endif()
  message(STATUS "sm2 Python module: ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
  # The module is a shared object and links the static libraries: they must be position-
  # independent. -fno-semantic-interposition keeps -fPIC from costing speed: without it GCC may
  # not inline or propagate across any exported function (docs/python.md, "Building").
  foreach(lib sm2_isa sm2_assembler sm2_emu sm2_runtime)
    if(TARGET ${lib})
      set_target_properties(${lib} PROPERTIES POSITION_INDEPENDENT_CODE ON)
      target_compile_options(${lib} PRIVATE -fno-semantic-interposition)
    endif()
  endforeach()
  add_subdirectory(python)
endif()
