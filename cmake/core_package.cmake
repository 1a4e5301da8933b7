# The installed CMake package of the engine (plain CMake build only), so that another project
# can write
#   find_package(sap_broadphase_core REQUIRED)
#   target_link_libraries(my_simulation PRIVATE sap_broadphase::core)
# The version is the one package.xml declares, so the two never disagree.
include(CMakePackageConfigHelpers)

file(READ ${CMAKE_CURRENT_SOURCE_DIR}/package.xml sap_package_xml)
string(REGEX MATCH "<version>([0-9.]+)</version>" sap_version_tag "${sap_package_xml}")
set(SAP_PACKAGE_VERSION ${CMAKE_MATCH_1})

set(sap_config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/${PROJECT_NAME}_core)
install(EXPORT ${PROJECT_NAME}_core_targets
  NAMESPACE ${PROJECT_NAME}::
  FILE ${PROJECT_NAME}_coreTargets.cmake
  DESTINATION ${sap_config_dir})
configure_package_config_file(
  ${CMAKE_CURRENT_LIST_DIR}/sap_broadphase_coreConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/${PROJECT_NAME}_coreConfig.cmake
  INSTALL_DESTINATION ${sap_config_dir})
write_basic_package_version_file(
  ${CMAKE_CURRENT_BINARY_DIR}/${PROJECT_NAME}_coreConfigVersion.cmake
  VERSION ${SAP_PACKAGE_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${CMAKE_CURRENT_BINARY_DIR}/${PROJECT_NAME}_coreConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/${PROJECT_NAME}_coreConfigVersion.cmake
  DESTINATION ${sap_config_dir})
