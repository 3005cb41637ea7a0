# The Python module `contactbench` (docs/python.md): found before the libraries are defined,
# since the extension links them and a shared object needs position-independent code.
option(CONTACTBENCH_PYTHON "Build the Python module where pybind11 and Python's headers are found" ON)
set(CONTACTBENCH_HAVE_PYTHON_MODULE OFF)
if(CONTACTBENCH_PYTHON)
  set(PYBIND11_FINDPYTHON ON)
  # Debian's Python, whose packages (python3-numpy, -pandas, -scipy, -pytest) the module uses,
  # rather than the first python3 on PATH (a pyenv shim, say); -DPython_EXECUTABLE=... chooses.
  if(NOT DEFINED Python_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python 3 COMPONENTS Interpreter Development.Module QUIET)
  if(Python_FOUND)
    find_package(pybind11 2.10 CONFIG QUIET)
  endif()
  if(Python_FOUND AND pybind11_FOUND)
    set(CONTACTBENCH_HAVE_PYTHON_MODULE ON)
    # The static archives go into a shared object: -fPIC for every target (executables get
    # -fPIE, Debian's default anyway). The cost is measured in docs/python.md.
    set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  else()
    message(STATUS "Python module not built: pybind11 (pybind11-dev) or Python's headers "
                   "(python3-dev) not found")
  endif()
endif()

# Called after the harness library exists.
function(contactbench_add_python_module)
  if(NOT CONTACTBENCH_HAVE_PYTHON_MODULE)
    return()
  endif()
  # build/python/contactbench: the package, importable with PYTHONPATH=build/python.
  set(package_dir ${PROJECT_BINARY_DIR}/python/contactbench)
  pybind11_add_module(contactbench_python MODULE ${PROJECT_SOURCE_DIR}/python/module.cc
    ${PROJECT_SOURCE_DIR}/python/step_bindings.cc)
  set_target_properties(contactbench_python PROPERTIES OUTPUT_NAME _core
    LIBRARY_OUTPUT_DIRECTORY ${package_dir})
  target_link_libraries(contactbench_python PRIVATE contactbench_harness)
  target_compile_options(contactbench_python PRIVATE ${CONTACTBENCH_WARNINGS})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/python/contactbench/*.py)
  foreach(source ${sources})
    get_filename_component(name ${source} NAME)
    configure_file(${source} ${package_dir}/${name} COPYONLY)
  endforeach()
  # Into the prefix's site-packages (lib/python3.X/site-packages, Python's posix_prefix scheme).
  execute_process(COMMAND ${Python_EXECUTABLE} -c
    "import sysconfig; print(sysconfig.get_path('platlib', 'posix_prefix', vars={'platbase': '.', 'base': '.'}))"
    OUTPUT_VARIABLE site OUTPUT_STRIP_TRAILING_WHITESPACE)
  string(REGEX REPLACE "^\\./" "" site "${site}")
  set(CONTACTBENCH_PYTHON_INSTALL_DIR ${site} CACHE STRING
      "Where cmake --install puts the Python package, relative to the prefix")
  install(TARGETS contactbench_python LIBRARY DESTINATION ${CONTACTBENCH_PYTHON_INSTALL_DIR}/contactbench)
  install(FILES ${sources} DESTINATION ${CONTACTBENCH_PYTHON_INSTALL_DIR}/contactbench)
  if(BUILD_TESTING)
    # tests/python_module/ with pytest (python3-pytest), against this build's module and driver;
    # skipped (exit status 77) without pytest or pandas.
    add_test(NAME python.module
      COMMAND ${Python_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/python_module/run_pytest.py)
    set_tests_properties(python.module PROPERTIES TIMEOUT 600 SKIP_RETURN_CODE 77 ENVIRONMENT
      "PYTHONPATH=${PROJECT_BINARY_DIR}/python;CONTACTBENCH_BINARY=$<TARGET_FILE:contactbench>;CONTACTBENCH_PLUGIN=${PROJECT_BINARY_DIR}/examples/plugin/libmin_newton.so")
  endif()
endfunction()
