# The Python module sap_broadphase (python/): the package python/sap_broadphase and its
# compiled part _sap_broadphase (pybind11, python/src/module.cpp), and its pytest suite.
#
# * catkin: catkin_python_setup() (CMakeLists.txt, setup.py) makes the workspace's Python
#   package sap_broadphase, which also holds the generated sap_broadphase.msg and .srv; the
#   compiled part is built into that package's devel directory and installed beside it.
# * plain CMake: the package is assembled in BUILD/python/sap_broadphase and installed to
#   PREFIX/lib/python3/dist-packages/sap_broadphase (PYTHONPATH=PREFIX/lib/python3/dist-packages).
#
# Needs Debian's python3-dev, pybind11-dev (or python3-pybind11) and, at run time, python3-numpy;
# skipped with a message when they are missing (-DSAP_BUILD_PYTHON=OFF skips it anyway).
option(SAP_BUILD_PYTHON "Build the Python module sap_broadphase (pybind11)" ON)
if(NOT SAP_BUILD_PYTHON)
  return()
endif()
# Debian's interpreter, whose packages (python3-numpy, python3-pybind11, python3-pytest) the
# module and its tests use: a pyenv or virtualenv python3 earlier in PATH may lack them. Under
# catkin, catkin's own (PYTHON_EXECUTABLE: scripts/setup.sh passes Debian's), even where a ROS
# package found another one first; -DPython3_EXECUTABLE chooses another in the plain build.
if(SAP_WITH_CATKIN AND PYTHON_EXECUTABLE)
  set(Python3_EXECUTABLE ${PYTHON_EXECUTABLE})
elseif(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
if(Python3_FOUND)
  find_package(pybind11 CONFIG QUIET)
endif()
if(NOT Python3_FOUND OR NOT pybind11_FOUND)
  message(STATUS "sap_broadphase: Python module skipped (needs python3-dev and pybind11-dev)")
  return()
endif()

if(SAP_WITH_CATKIN)
  set(SAP_PYTHON_PACKAGE_DIR ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_PYTHON_DESTINATION})
  set(SAP_PYTHON_INSTALL_DIR ${CATKIN_PACKAGE_PYTHON_DESTINATION})
  set(SAP_PYTHON_PATH ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_PYTHON_DESTINATION})
else()
  set(SAP_PYTHON_PATH ${CMAKE_BINARY_DIR}/python)
  set(SAP_PYTHON_PACKAGE_DIR ${SAP_PYTHON_PATH}/sap_broadphase)
  set(SAP_PYTHON_INSTALL_DIR lib/python3/dist-packages/sap_broadphase)
endif()

# The engine goes into a shared object: its static library must be position independent.
set_target_properties(${PROJECT_NAME}_core PROPERTIES POSITION_INDEPENDENT_CODE ON)
# NO_EXTRAS: no link-time optimisation (the engine is a separate library; it only adds link time)
pybind11_add_module(${PROJECT_NAME}_python NO_EXTRAS python/src/module.cpp)
target_link_libraries(${PROJECT_NAME}_python PRIVATE ${PROJECT_NAME}_core)
set_target_properties(${PROJECT_NAME}_python PROPERTIES OUTPUT_NAME _sap_broadphase
  LIBRARY_OUTPUT_DIRECTORY ${SAP_PYTHON_PACKAGE_DIR})
#catkin_lint: ignore_once undefined_target (pybind11_add_module defines it)
install(TARGETS ${PROJECT_NAME}_python LIBRARY DESTINATION ${SAP_PYTHON_INSTALL_DIR})
if(NOT SAP_WITH_CATKIN)
  # The package's Python files beside the compiled part, copied on every build so that an edit
  # is picked up (catkin's package reads them from the source directory).
  add_custom_command(TARGET ${PROJECT_NAME}_python POST_BUILD
    COMMAND ${CMAKE_COMMAND} -E copy_if_different
      ${CMAKE_CURRENT_SOURCE_DIR}/python/sap_broadphase/__init__.py ${SAP_PYTHON_PACKAGE_DIR}/)
  install(FILES python/sap_broadphase/__init__.py DESTINATION ${SAP_PYTHON_INSTALL_DIR})
endif()

# pytest (python/tests), through python/tests/run_tests.py, which writes the JUnit file that
# scripts/test.sh and scripts/test_no_ros.sh count and fails when no test was collected.
if(SAP_TESTING)
  if(SAP_WITH_CATKIN)
    set(SAP_PYTEST_XML ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/pytest-python.xml)
    catkin_run_tests_target("pytest" "python" "pytest-python.xml"
      COMMAND "${Python3_EXECUTABLE} ${CMAKE_CURRENT_SOURCE_DIR}/python/tests/run_tests.py --ros ${SAP_PYTEST_XML}"
      DEPENDENCIES ${PROJECT_NAME}_python)
  else()
    add_test(NAME python_tests COMMAND ${Python3_EXECUTABLE}
      ${CMAKE_CURRENT_SOURCE_DIR}/python/tests/run_tests.py ${SAP_TEST_RESULTS_DIR}/pytest-python.xml)
    set_tests_properties(python_tests PROPERTIES ENVIRONMENT "PYTHONPATH=${SAP_PYTHON_PATH}")
  endif()
endif()
