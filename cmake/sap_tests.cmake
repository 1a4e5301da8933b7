# One way to register a GoogleTest executable under catkin and under plain CMake, so that
# test/tests.cmake and its fragments read the same in both builds.
#
# sap_add_gtest(NAME SOURCES...): the sources include their own main() (test/core/test_main.cpp
# or test/stress/stress_main.cpp), because catkin_add_gtest links gtest without gtest_main.
# Under catkin the test joins `catkin_make run_tests`; under plain CMake it is one ctest test
# that writes its JUnit XML to ${SAP_TEST_RESULTS_DIR}, the file scripts/test_no_ros.sh counts.
#
# SAP_TESTING says whether tests are built: under catkin when CATKIN_ENABLE_TESTING is on,
# under plain CMake when SAP_BUILD_TESTS is on (off by default: a consumer's build needs
# neither GoogleTest nor the tests' build time; scripts/test_no_ros.sh turns it on) and
# GoogleTest is installed. (Not CTest's BUILD_TESTING: CGAL's package config, found by the
# benchmarks, declares it OFF.)
if(SAP_WITH_CATKIN)
  set(SAP_TESTING ${CATKIN_ENABLE_TESTING})
else()
  option(SAP_BUILD_TESTS "Build the ROS-free tests (needs GoogleTest)" OFF)
  set(SAP_TESTING OFF)
  if(SAP_BUILD_TESTS)
    find_package(GTest)
    if(GTest_FOUND)
      enable_testing()
      set(SAP_TESTING ON)
      set(SAP_TEST_RESULTS_DIR ${CMAKE_BINARY_DIR}/test_results)
    else()
      message(STATUS "sap_broadphase: GoogleTest not found (Debian: libgtest-dev), tests skipped")
    endif()
  endif()
endif()

function(sap_add_gtest inName)
  if(SAP_WITH_CATKIN)
    catkin_add_gtest(${inName} ${ARGN})
  else()
    add_executable(${inName} ${ARGN})
    target_link_libraries(${inName} GTest::gtest)
    add_test(NAME ${inName}
      COMMAND ${inName} --gtest_output=xml:${SAP_TEST_RESULTS_DIR}/${inName}.xml)
  endif()
endfunction()
