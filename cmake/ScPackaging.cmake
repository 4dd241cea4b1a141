# SPDX-License-Identifier: MIT
# Installs the exported targets and the SmartCollisionConfig package files.
include(CMakePackageConfigHelpers)

set(SC_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/SmartCollision)

install(EXPORT SmartCollisionTargets
        NAMESPACE SmartCollision::
        DESTINATION ${SC_INSTALL_CMAKEDIR})

# The config finds Bullet (pkg-config) only when the plugin was built and installed;
# the plugin's target is in its own export set, loaded only when Bullet is found.
if(TARGET sc_bullet)
  set(SC_HAS_BULLET_PLUGIN ON)
  install(EXPORT SmartCollisionBulletTargets
          NAMESPACE SmartCollision::
          DESTINATION ${SC_INSTALL_CMAKEDIR})
else()
  set(SC_HAS_BULLET_PLUGIN OFF)
endif()

configure_package_config_file(
  ${CMAKE_CURRENT_SOURCE_DIR}/cmake/SmartCollisionConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/SmartCollisionConfig.cmake
  INSTALL_DESTINATION ${SC_INSTALL_CMAKEDIR})

write_basic_package_version_file(
  ${CMAKE_CURRENT_BINARY_DIR}/SmartCollisionConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)

install(FILES ${CMAKE_CURRENT_BINARY_DIR}/SmartCollisionConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/SmartCollisionConfigVersion.cmake
        DESTINATION ${SC_INSTALL_CMAKEDIR})
