# The distributed broad phase under mpirun (cmake/distributed.cmake builds it when MPI is
# found). Registered in the plain CMake build only, so that the test command
# (scripts/test.sh, which runs both builds) runs these mpirun jobs once; their JUnit XML lands
# with the other ROS-free tests'. About a minute on 2 cores.
if(SAP_WITH_CATKIN OR NOT TARGET ${PROJECT_NAME}_distributed)
  return()
endif()

# The MPI program the exactness tests start under mpirun.
add_executable(distributed_check test/distributed/distributed_check_main.cpp)
target_link_libraries(distributed_check ${PROJECT_NAME}_distributed)

sap_add_gtest(test_distributed test/distributed/test_distributed.cpp test/core/test_main.cpp)
target_include_directories(test_distributed PRIVATE test/core)
add_dependencies(test_distributed distributed_check sap_pairs_mpi sap_pairs)
target_compile_definitions(test_distributed PRIVATE
  SAP_MPIEXEC="${MPIEXEC_EXECUTABLE}"
  DISTRIBUTED_CHECK_EXE="$<TARGET_FILE:distributed_check>"
  SAP_PAIRS_EXE="$<TARGET_FILE:sap_pairs>"
  SAP_PAIRS_MPI_EXE="$<TARGET_FILE:sap_pairs_mpi>")
