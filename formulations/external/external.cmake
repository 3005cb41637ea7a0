# Formulations registered at run time (docs/your-own-method.md): the step as data and the
# formulation around a callable. No dependency beyond the library's own.
target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/callback_formulation.cc
  ${CMAKE_CURRENT_LIST_DIR}/step_system.cc)
