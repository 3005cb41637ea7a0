# petsc-rsls and petsc-ssls, with PETSc's SNESVI (Debian: petsc-dev, scripts/packages.txt; PETSc
# 3.18 with Open MPI). With PETSc: the adapter and the formulations; without: the stub, whose
# PetscAvailable() is false. The MCP (petsc_mcp.cc) needs no PETSc and is built either way (its
# tests check the function and the Jacobian in every build).
option(CONTACTBENCH_WITH_PETSC "Build the PETSc SNESVI formulations (needs petsc-dev)" ON)

set(CONTACTBENCH_HAVE_PETSC OFF)
if(CONTACTBENCH_WITH_PETSC)
  # PETSc ships pkg-config only (PETSc.pc; Debian's under /usr/lib/petsc, the PETSC_DIR that
  # PETSc's own makefiles use). Its headers include mpi.h, which PETSc.pc does not locate.
  find_package(PkgConfig REQUIRED)
  set(CONTACTBENCH_PETSC_DIR "$ENV{PETSC_DIR}")
  if(NOT CONTACTBENCH_PETSC_DIR)
    set(CONTACTBENCH_PETSC_DIR /usr/lib/petsc)
  endif()
  set(ENV{PKG_CONFIG_PATH}
      "${CONTACTBENCH_PETSC_DIR}/lib/pkgconfig:$ENV{PKG_CONFIG_PATH}")
  pkg_check_modules(PETSC IMPORTED_TARGET PETSc)
  # The project is C++ only: MPI's C library through the CXX component, without the
  # (deprecated) MPI C++ bindings.
  set(MPI_CXX_SKIP_MPICXX ON)
  find_package(MPI COMPONENTS CXX QUIET)
  if(PETSC_FOUND AND MPI_CXX_FOUND)
    set(CONTACTBENCH_HAVE_PETSC ON)
  else()
    message(WARNING "PETSc (with MPI) not found: the PETSc formulations are unavailable")
  endif()
endif()

target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/petsc_mcp.cc
  ${CMAKE_CURRENT_LIST_DIR}/petsc_mcp_rows.cc)
if(CONTACTBENCH_HAVE_PETSC)
  target_sources(contactbench_formulations PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/petsc_adapter.cc
    ${CMAKE_CURRENT_LIST_DIR}/petsc_process.cc
    ${CMAKE_CURRENT_LIST_DIR}/petsc_unused_options.cc
    ${CMAKE_CURRENT_LIST_DIR}/snes_glue.cc
    ${CMAKE_CURRENT_LIST_DIR}/petsc_vi_formulation.cc)
  target_link_libraries(contactbench_formulations PRIVATE PkgConfig::PETSC MPI::MPI_CXX)
  # For code that asks at compile time (the tests); the formulations ask PetscAvailable().
  target_compile_definitions(contactbench_formulations PUBLIC CONTACTBENCH_HAVE_PETSC=1)
  # The installed (static) library needs PETSc whichever components a consumer asks for; not
  # finding it makes the package not found, with the reason.
  string(APPEND CONTACTBENCH_FIND_DEPENDENCIES
    "find_dependency(PkgConfig)\npkg_check_modules(PETSC QUIET IMPORTED_TARGET PETSc)\n"
    "if(NOT PETSC_FOUND)\n"
    "  set(contactbench_FOUND FALSE)\n"
    "  set(contactbench_NOT_FOUND_MESSAGE \"contactbench was built with PETSc, whose PETSc.pc "
    "pkg-config does not find (add ${CONTACTBENCH_PETSC_DIR}/lib/pkgconfig to "
    "PKG_CONFIG_PATH)\")\n"
    "  return()\n"
    "endif()\n"
    "set(MPI_CXX_SKIP_MPICXX ON)\nfind_dependency(MPI COMPONENTS CXX)\n")
else()
  target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/petsc_stub.cc)
endif()
