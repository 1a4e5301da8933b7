# The distributed broad phase over MPI (docs/DISTRIBUTED.md): built only when an MPI with C++
# support is found (Debian: libopenmpi-dev openmpi-bin); without it the engine, the tools and
# the tests are exactly as before, and `sap_bench -e distributed` says MPI is missing.
find_package(MPI QUIET COMPONENTS CXX)
if(NOT MPI_CXX_FOUND)
  message(STATUS "sap_broadphase: MPI not found, the distributed broad phase is not built")
  return()
endif()
message(STATUS "sap_broadphase: distributed broad phase with ${MPIEXEC_EXECUTABLE}")

add_library(${PROJECT_NAME}_distributed
  src/distributed/slab_cuts.cpp
  src/distributed/distributed_broadphase.cpp
)
target_include_directories(${PROJECT_NAME}_distributed
  PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> PRIVATE src/distributed src)
target_link_libraries(${PROJECT_NAME}_distributed PUBLIC ${PROJECT_NAME}_core MPI::MPI_CXX)

# mpirun -np R sap_pairs_mpi FILE: sap_pairs' contract, computed by R ranks.
add_executable(sap_pairs_mpi src/apps/sap_pairs_mpi_main.cpp src/apps/pairs_options.cpp
  src/apps/cli_args.cpp)
target_link_libraries(sap_pairs_mpi ${PROJECT_NAME}_distributed)

# The worker of `sap_bench -e distributed`, which sap_bench starts under mpirun (with the
# benchmarks only, SAP_BUILD_BENCHMARKS).
if(TARGET sap_bench)
  add_executable(sap_bench_distributed ${SAP_BENCH_DIR}/distributed_bench_main.cpp)
  target_link_libraries(sap_bench_distributed ${PROJECT_NAME}_distributed OpenMP::OpenMP_CXX)
  add_dependencies(sap_bench sap_bench_distributed)
  target_compile_definitions(sap_bench PRIVATE
    SAP_BENCH_DISTRIBUTED_WORKER="$<TARGET_FILE:sap_bench_distributed>"
    SAP_MPIEXEC="${MPIEXEC_EXECUTABLE}")
endif()

# The tool and the library it links (shared under catkin) are installed; the headers are not
# part of the installed engine package (include/sap_broadphase/core), which is MPI-free.
install(TARGETS ${PROJECT_NAME}_distributed sap_pairs_mpi
  ARCHIVE DESTINATION ${SAP_LIB_DESTINATION}
  LIBRARY DESTINATION ${SAP_LIB_DESTINATION}
  RUNTIME DESTINATION ${SAP_BIN_DESTINATION})
