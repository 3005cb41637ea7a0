# The distributed formulations (dist-*): the step systems over MPI with PETSc (petsc-dev, the
# PETSc of petsc.cmake, included before this file). With PETSc: the distributed system and
# the formulations; without: the stub, whose DistAvailable() is false. The element and pair
# partition and the per-process contact-only model need no PETSc and are built either way (their
# tests run in every build).
target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/element_partition.cc
  ${CMAKE_CURRENT_LIST_DIR}/own_pairs_model.cc)
if(CONTACTBENCH_HAVE_PETSC)
  target_sources(contactbench_formulations PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/dist_line_search.cc
    ${CMAKE_CURRENT_LIST_DIR}/petsc_dist_adapter.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_formulation.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_implicit_fb.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_nonsmooth_fb.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_active_set.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_petsc_rsls.cc
    ${CMAKE_CURRENT_LIST_DIR}/dist_petsc_ssls.cc
    ${CMAKE_CURRENT_LIST_DIR}/field_split.cc
    ${CMAKE_CURRENT_LIST_DIR}/node_blocks.cc
    ${CMAKE_CURRENT_LIST_DIR}/parallel_libraries.cc)
else()
  target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/petsc_dist_stub.cc)
endif()
if(CONTACTBENCH_HAVE_PETSC)
  # dlsym / dladdr / dl_iterate_phdr: which library serves MPI and MUMPS (parallel_libraries.cc).
  target_link_libraries(contactbench_formulations PRIVATE ${CMAKE_DL_LIBS})
endif()
