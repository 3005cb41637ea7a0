# The processes of a run (processes.h), a part of the core library: with MPI (found with PETSc
# by formulations/petsc/petsc.cmake, included before this file) processes_mpi.cc, else the
# one-process stand-in processes_serial.cc; the launcher's count (launched_processes.cc) in both.
target_sources(contactbench_core PRIVATE ${CMAKE_CURRENT_LIST_DIR}/launched_processes.cc)
if(CONTACTBENCH_HAVE_PETSC)
  target_sources(contactbench_core PRIVATE ${CMAKE_CURRENT_LIST_DIR}/processes_mpi.cc)
  target_link_libraries(contactbench_core PRIVATE MPI::MPI_CXX)
else()
  target_sources(contactbench_core PRIVATE ${CMAKE_CURRENT_LIST_DIR}/processes_serial.cc)
endif()
