# What every formulation may share: the settings (config), the step equations of the equation
# formulations, and what the energy formulations ask of a step.
target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/captured_stderr.cc
  ${CMAKE_CURRENT_LIST_DIR}/config.cc
  ${CMAKE_CURRENT_LIST_DIR}/energy_step.cc
  ${CMAKE_CURRENT_LIST_DIR}/fischer_burmeister.cc
  ${CMAKE_CURRENT_LIST_DIR}/reduced_step_solve.cc
  ${CMAKE_CURRENT_LIST_DIR}/reduced_step_system.cc
  ${CMAKE_CURRENT_LIST_DIR}/start_solvers.cc
  ${CMAKE_CURRENT_LIST_DIR}/step_equation_solve.cc
  ${CMAKE_CURRENT_LIST_DIR}/step_equations.cc
  ${CMAKE_CURRENT_LIST_DIR}/step_rows.cc
  ${CMAKE_CURRENT_LIST_DIR}/step_start.cc)
