# nlopt-merit, nlopt-energy and nlopt-mpcc, with NLopt (Debian: libnlopt-cxx-dev,
# scripts/packages.txt). With NLopt: the adapter and the formulations; without: the stub, whose
# NloptAvailable() is false. The options and the NLPs' functions (nlopt_options.cc,
# nlopt_problems.cc) need no NLopt and are built either way (a bad option is reported in every
# build; the tests check the derivatives in every build).
option(CONTACTBENCH_WITH_NLOPT "Build the NLopt formulations (needs libnlopt-cxx-dev)" ON)

set(CONTACTBENCH_HAVE_NLOPT OFF)
if(CONTACTBENCH_WITH_NLOPT)
  find_package(NLopt CONFIG)
  if(NLopt_FOUND)
    set(CONTACTBENCH_HAVE_NLOPT ON)
  else()
    message(WARNING "NLopt not found: the NLopt formulations are unavailable")
  endif()
endif()

target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/nlopt_options.cc
  ${CMAKE_CURRENT_LIST_DIR}/nlopt_problems.cc)
if(CONTACTBENCH_HAVE_NLOPT)
  target_sources(contactbench_formulations PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/nlopt_adapter.cc
    ${CMAKE_CURRENT_LIST_DIR}/nlopt_energy.cc
    ${CMAKE_CURRENT_LIST_DIR}/nlopt_merit.cc
    ${CMAKE_CURRENT_LIST_DIR}/nlopt_mpcc.cc)
  target_link_libraries(contactbench_formulations PRIVATE ${NLOPT_LIBRARIES})
  target_include_directories(contactbench_formulations SYSTEM PRIVATE ${NLOPT_INCLUDE_DIRS})
  # For code that asks at compile time (the tests); the formulations ask NloptAvailable().
  target_compile_definitions(contactbench_formulations PUBLIC CONTACTBENCH_HAVE_NLOPT=1)
  string(APPEND CONTACTBENCH_FIND_DEPENDENCIES "find_dependency(NLopt CONFIG)\n")
else()
  target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/nlopt_stub.cc)
endif()
