# Every dependency comes from a Debian package (see README "Dependencies").
find_package(PkgConfig REQUIRED)

# Ipopt 3.11: its pkg-config cflags carry -DHAVE_CSTDDEF, which the headers need.
pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET ipopt)
pkg_check_modules(FFTW REQUIRED IMPORTED_TARGET fftw3)

find_package(NLopt REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(benchmark REQUIRED)
find_package(GTest REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(Threads REQUIRED)

# SuiteSparse 5.x ships no CMake config on Debian 12.
find_path(SUITESPARSE_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
foreach(lib umfpack klu cholmod amd colamd btf suitesparseconfig)
  find_library(SUITESPARSE_${lib}_LIBRARY NAMES ${lib} REQUIRED)
  list(APPEND SUITESPARSE_LIBRARIES ${SUITESPARSE_${lib}_LIBRARY})
endforeach()
add_library(ocpb_suitesparse INTERFACE)
target_include_directories(ocpb_suitesparse SYSTEM INTERFACE ${SUITESPARSE_INCLUDE_DIR})
target_link_libraries(ocpb_suitesparse INTERFACE ${SUITESPARSE_LIBRARIES})
