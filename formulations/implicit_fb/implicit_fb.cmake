# implicit-fb: no dependency beyond the library's own.
target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/eta_equation.cc
  ${CMAKE_CURRENT_LIST_DIR}/implicit_fb.cc
  ${CMAKE_CURRENT_LIST_DIR}/implicit_fb_rows.cc
  ${CMAKE_CURRENT_LIST_DIR}/implicit_fb_system.cc)
