# The exported CMake package: another project does find_package(lodestone) and links
# lodestone::obs, lodestone::io, ...
include(CMakePackageConfigHelpers)
set(LODESTONE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/lodestone)
install(EXPORT lodestoneTargets NAMESPACE lodestone:: DESTINATION ${LODESTONE_CMAKE_DIR})
configure_package_config_file(
    ${CMAKE_CURRENT_SOURCE_DIR}/cmake/lodestoneConfig.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/lodestoneConfig.cmake
    INSTALL_DESTINATION ${LODESTONE_CMAKE_DIR})
write_basic_package_version_file(
    ${CMAKE_CURRENT_BINARY_DIR}/lodestoneConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES
    ${CMAKE_CURRENT_BINARY_DIR}/lodestoneConfig.cmake
    ${CMAKE_CURRENT_BINARY_DIR}/lodestoneConfigVersion.cmake
    ${CMAKE_CURRENT_SOURCE_DIR}/cmake/LodestoneDependencies.cmake
    DESTINATION ${LODESTONE_CMAKE_DIR})
