# siconos-lemke, siconos-newton-fb and siconos-newton-min, with Siconos numerics (Debian:
# libsiconos-numerics-dev, scripts/packages.txt). Debian's siconos CMake package config is broken
# (it names components and targets the package does not ship), so the headers and the library
# are located directly. With Siconos: the adapter and the formulations; without: the stub, whose
# SiconosAvailable() is false. The LCP reduction (siconos_lcp.cc) needs no Siconos and is built
# either way (its tests check it in every build).
option(CONTACTBENCH_WITH_SICONOS "Build the Siconos formulations (needs libsiconos-numerics-dev)"
       ON)

set(CONTACTBENCH_HAVE_SICONOS OFF)
if(CONTACTBENCH_WITH_SICONOS)
  find_path(SICONOS_NUMERICS_INCLUDE_DIR NAMES LCP_Solvers.h PATH_SUFFIXES siconos/numerics)
  find_path(SICONOS_CONFIG_INCLUDE_DIR NAMES SiconosConfig.h PATH_SUFFIXES siconos)
  find_library(SICONOS_NUMERICS_LIBRARY NAMES siconos_numerics)
  if(SICONOS_NUMERICS_INCLUDE_DIR AND SICONOS_CONFIG_INCLUDE_DIR AND SICONOS_NUMERICS_LIBRARY)
    set(CONTACTBENCH_HAVE_SICONOS ON)
  else()
    message(WARNING "Siconos numerics not found: the Siconos formulations are unavailable")
  endif()
endif()

target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/siconos_lcp.cc)
if(CONTACTBENCH_HAVE_SICONOS)
  target_sources(contactbench_formulations PRIVATE
    ${CMAKE_CURRENT_LIST_DIR}/siconos_adapter.cc
    ${CMAKE_CURRENT_LIST_DIR}/siconos_lcp_formulation.cc)
  # -isystem keeps the warnings of Siconos's headers (included by the adapter only) out of
  # -Werror.
  target_include_directories(contactbench_formulations SYSTEM PRIVATE
    ${SICONOS_NUMERICS_INCLUDE_DIR} ${SICONOS_CONFIG_INCLUDE_DIR})
  target_link_libraries(contactbench_formulations PRIVATE ${SICONOS_NUMERICS_LIBRARY})
  # Its version for run.json: the headers carry none, so the library file linked (symbolic
  # links resolved) and, where dpkg knows the file, the Debian package's version.
  file(REAL_PATH "${SICONOS_NUMERICS_LIBRARY}" siconos_library_file)
  get_filename_component(siconos_version "${siconos_library_file}" NAME)
  execute_process(COMMAND dpkg-query -S "${siconos_library_file}"
                  OUTPUT_VARIABLE siconos_package OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE failed ERROR_QUIET)
  if(NOT failed)
    string(REGEX REPLACE ":.*" "" siconos_package "${siconos_package}")
    execute_process(COMMAND dpkg-query -W "-f=\${Version}" "${siconos_package}"
                    OUTPUT_VARIABLE siconos_package_version OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed)
      set(siconos_version "${siconos_package_version} (${siconos_version})")
    endif()
  endif()
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/siconos_adapter.cc PROPERTIES
    COMPILE_DEFINITIONS CONTACTBENCH_SICONOS_VERSION="${siconos_version}")
  # For code that asks at compile time (the tests); the formulations ask SiconosAvailable().
  target_compile_definitions(contactbench_formulations PUBLIC CONTACTBENCH_HAVE_SICONOS=1)
  # The installed (static) library links the numerics library by its path.
  string(APPEND CONTACTBENCH_FIND_DEPENDENCIES
    "if(NOT EXISTS \"${SICONOS_NUMERICS_LIBRARY}\")\n"
    "  set(contactbench_FOUND FALSE)\n"
    "  set(contactbench_NOT_FOUND_MESSAGE \"contactbench was built with Siconos numerics, "
    "which is no longer at ${SICONOS_NUMERICS_LIBRARY}\")\n"
    "  return()\n"
    "endif()\n")
else()
  target_sources(contactbench_formulations PRIVATE ${CMAKE_CURRENT_LIST_DIR}/siconos_stub.cc)
endif()
