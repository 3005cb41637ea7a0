# ipopt-energy and ipopt-mpcc, with Ipopt (Debian: coinor-libipopt-dev, scripts/packages.txt).
# With Ipopt: the adapter and the formulations; without: the stub, whose IpoptAvailable() is
# false. The NLPs (ipopt_nlp.h: ipopt_energy_nlp.cc, ipopt_mpcc_nlp.cc and their helpers) need
# no Ipopt and are built either way (their tests check the derivatives in every build).
option(CONTACTBENCH_WITH_IPOPT "Build the Ipopt formulations (needs coinor-libipopt-dev)" ON)

set(CONTACTBENCH_HAVE_IPOPT OFF)
if(CONTACTBENCH_WITH_IPOPT)
  # Ipopt 3.11 ships pkg-config only (adds -I.../coin -DHAVE_CSTDDEF).
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(IPOPT IMPORTED_TARGET ipopt)
  if(IPOPT_FOUND)
    set(CONTACTBENCH_HAVE_IPOPT ON)
  else()
    message(WARNING "Ipopt not found: the Ipopt formulations are unavailable")
  endif()
endif()

target_sources(contactbench_formulations PRIVATE
  ${CMAKE_CURRENT_LIST_DIR}/ipopt_colouring.cc
  ${CMAKE_CURRENT_LIST_DIR}/ipopt_energy_nlp.cc
  ${CMAKE_CURRENT_LIST_DIR}/ipopt_mpcc_nlp.cc
  ${CMAKE_CURRENT_LIST_DIR}/ipopt_sparse.cc)
if(CONTACTBENCH_HAVE_IPOPT)
  target_sources(contactbench_formulations PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/ipopt_adapter.cc
    ${CMAKE_CURRENT_LIST_DIR}/ipopt_energy.cc
    ${CMAKE_CURRENT_LIST_DIR}/ipopt_mpcc.cc)
  target_link_libraries(contactbench_formulations PRIVATE PkgConfig::IPOPT)
  # For code that asks at compile time (the tests); the formulations ask IpoptAvailable().
  target_compile_definitions(contactbench_formulations PUBLIC CONTACTBENCH_HAVE_IPOPT=1)
  string(APPEND CONTACTBENCH_FIND_DEPENDENCIES
    "find_dependency(PkgConfig)\npkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET ipopt)\n")
else()
  target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/ipopt_stub.cc)
endif()
