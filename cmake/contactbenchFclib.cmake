# FCLIB files (src/io/fclib_file.h) with HDF5's C API (Debian: libhdf5-dev, scripts/packages.txt).
# With HDF5: the reader and writer in src/io/fclib/; without: the stub, which refuses FCLIB
# files with the reason. libfclib-dev is not needed to build: its reader exits the process on a
# bad file, so the suite reads the format itself; the tests use it, when present, to check that
# FCLIB's own reader reads what the suite writes.
option(CONTACTBENCH_WITH_HDF5 "Read and write FCLIB problem files (needs libhdf5-dev)" ON)

set(CONTACTBENCH_HAVE_HDF5 OFF)
if(CONTACTBENCH_WITH_HDF5)
  # The serial library by its own pkg-config name: Debian's plain `hdf5` follows the
  # alternatives and names the MPI build when libhdf5-mpi-dev is installed (PETSc pulls it in).
  # CMake's FindHDF5 needs the C language enabled, which this C++ project does not.
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(HDF5 IMPORTED_TARGET hdf5-serial)
  if(HDF5_FOUND)
    set(CONTACTBENCH_HAVE_HDF5 ON)
  else()
    message(WARNING "HDF5 (hdf5-serial) not found: FCLIB problem files are refused")
  endif()
endif()

set(CONTACTBENCH_FCLIB_DIR ${PROJECT_SOURCE_DIR}/src/io/fclib)
if(CONTACTBENCH_HAVE_HDF5)
  target_sources(contactbench_core PRIVATE
    ${CONTACTBENCH_FCLIB_DIR}/hdf5_file.cc
    ${CONTACTBENCH_FCLIB_DIR}/fclib_matrix.cc
    ${CONTACTBENCH_FCLIB_DIR}/fclib_reader.cc
    ${CONTACTBENCH_FCLIB_DIR}/fclib_writer.cc)
  target_link_libraries(contactbench_core PRIVATE PkgConfig::HDF5)
  target_compile_definitions(contactbench_core PUBLIC CONTACTBENCH_HAVE_HDF5=1)
  string(APPEND CONTACTBENCH_FIND_DEPENDENCIES
    "find_dependency(PkgConfig)\npkg_check_modules(HDF5 REQUIRED IMPORTED_TARGET hdf5-serial)\n")
else()
  target_sources(contactbench_core PRIVATE ${CONTACTBENCH_FCLIB_DIR}/fclib_stub.cc)
endif()
