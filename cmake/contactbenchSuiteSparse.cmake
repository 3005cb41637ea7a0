# SuiteSparse as one imported target, contactbench::SuiteSparse: UMFPACK, KLU and CHOLMOD with
# the libraries they need, LAPACK (CHOLMOD runs on it, and solvers/dense_cholesky.h factorises
# the dense contact block with it; libsuitesparse-dev depends on liblapack-dev), and the include
# directory (the library's headers include cholmod.h). Debian's libsuitesparse-dev (5.x) ships
# no CMake package, so the build and the installed package config both find it with this file:
# the exported targets name the target, not the paths of the machine that built them. Sets
# contactbench_SuiteSparse_FOUND.
if(TARGET contactbench::SuiteSparse)
  set(contactbench_SuiteSparse_FOUND TRUE)
  return()
endif()
set(contactbench_SuiteSparse_FOUND FALSE)
find_path(CONTACTBENCH_SUITESPARSE_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
set(_contactbench_suitesparse_libraries "")
foreach(_name umfpack klu btf cholmod amd colamd suitesparseconfig lapack)
  string(TOUPPER "${_name}" _upper)
  find_library(CONTACTBENCH_${_upper}_LIBRARY ${_name})
  if(NOT CONTACTBENCH_${_upper}_LIBRARY)
    return()
  endif()
  list(APPEND _contactbench_suitesparse_libraries "${CONTACTBENCH_${_upper}_LIBRARY}")
endforeach()
if(NOT CONTACTBENCH_SUITESPARSE_INCLUDE_DIR)
  return()
endif()
add_library(contactbench::SuiteSparse INTERFACE IMPORTED)
set_target_properties(contactbench::SuiteSparse PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${CONTACTBENCH_SUITESPARSE_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${_contactbench_suitesparse_libraries}")
set(contactbench_SuiteSparse_FOUND TRUE)
