# `cmake --install` of OCPBench's libraries and headers, with an exported package so that a
# project outside this tree can write
#
#   find_package(OCPBench REQUIRED)
#   target_link_libraries(my_target PRIVATE OCPBench::solvers OCPBench::problems)
#   target_link_libraries(my_ocpbench PRIVATE OCPBench::cli)   # the whole command line
#
# and include "core/autodiff_ocp.h", "problems/registry.h", "solvers/registry.h",
# "bench/cli/main.h" (ocpb::Main), ... (see examples/user_example/). Layout under the prefix:
#   include/ocpbench/{core,transcriptions,solvers,problems,drivers,bench}/**.h
#   lib/libocpb_*.a
#   lib/cmake/OCPBench/{OCPBenchConfig,OCPBenchConfigVersion,OCPBenchTargets}.cmake
#   bin/ocpbench
# Included from the top-level CMakeLists.txt after every target exists.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(OCPB_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/ocpbench)
set(OCPB_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/OCPBench)

# The libraries a user links, and the project targets they depend on (exported with them;
# imported third-party targets are found again by OCPBenchConfig.cmake).
set(OCPB_EXPORTED_TARGETS)
foreach(target ocpb_core ocpb_transcriptions ocpb_solvers ocpb_channel ocpb_problems
               ocpb_online ocpb_cli ocpb_suitesparse)
  if(NOT TARGET ${target})
    continue()
  endif()
  list(APPEND OCPB_EXPORTED_TARGETS ${target})
  string(REGEX REPLACE "^ocpb_" "" export_name ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${export_name})
  # ocpb_library() publishes the source tree as the include directory; installed consumers
  # get include/ocpbench instead (same relative paths: "core/ocp.h").
  get_target_property(includes ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(includes AND PROJECT_SOURCE_DIR IN_LIST includes)
    list(REMOVE_ITEM includes ${PROJECT_SOURCE_DIR})
    list(PREPEND includes
      "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>" "$<INSTALL_INTERFACE:${OCPB_INSTALL_INCLUDEDIR}>")
    set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${includes}")
  endif()
endforeach()

install(TARGETS ${OCPB_EXPORTED_TARGETS}
  EXPORT OCPBenchTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
if(TARGET ocpbench)
  install(TARGETS ocpbench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

foreach(dir core transcriptions solvers problems drivers bench)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/
    DESTINATION ${OCPB_INSTALL_INCLUDEDIR}/${dir}
    FILES_MATCHING PATTERN "*.h")
endforeach()

install(EXPORT OCPBenchTargets
  NAMESPACE OCPBench::
  DESTINATION ${OCPB_INSTALL_CMAKEDIR})

# The package configuration: third-party dependencies first (the same packages
# cmake/Dependencies.cmake uses; SuiteSparse comes in as absolute library paths), then the
# exported targets.
file(WRITE ${PROJECT_BINARY_DIR}/OCPBenchConfig.cmake.in [=[
@PACKAGE_INIT@
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.4 NO_MODULE)
find_dependency(NLopt)
find_dependency(Threads)
find_dependency(nlohmann_json 3.10)
find_dependency(fmt)
find_dependency(CLI11)
find_dependency(PkgConfig)
if(NOT TARGET PkgConfig::IPOPT)
  pkg_check_modules(IPOPT REQUIRED IMPORTED_TARGET ipopt)
endif()
if(NOT TARGET PkgConfig::FFTW)
  pkg_check_modules(FFTW REQUIRED IMPORTED_TARGET fftw3)
endif()
include("${CMAKE_CURRENT_LIST_DIR}/OCPBenchTargets.cmake")
check_required_components(OCPBench)
]=])
configure_package_config_file(${PROJECT_BINARY_DIR}/OCPBenchConfig.cmake.in
  ${PROJECT_BINARY_DIR}/OCPBenchConfig.cmake
  INSTALL_DESTINATION ${OCPB_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/OCPBenchConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/OCPBenchConfig.cmake
  ${PROJECT_BINARY_DIR}/OCPBenchConfigVersion.cmake
  DESTINATION ${OCPB_INSTALL_CMAKEDIR})
