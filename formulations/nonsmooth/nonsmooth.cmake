# nonsmooth-fb and active-set: no dependency beyond the library's own.
target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/active_set.cc
  ${CMAKE_CURRENT_LIST_DIR}/nonsmooth_fb.cc
  ${CMAKE_CURRENT_LIST_DIR}/nonsmooth_formulation.cc
  ${CMAKE_CURRENT_LIST_DIR}/nonsmooth_restart.cc
  ${CMAKE_CURRENT_LIST_DIR}/nonsmooth_rows.cc
  ${CMAKE_CURRENT_LIST_DIR}/nonsmooth_system.cc)
