# `cmake --install build --prefix P` installs the vgi tool, the libraries as
# vgi:: targets (vgi::core, vgi::voxelize, vgi::traverse, vgi::illum, vgi::experiments,
# vgi::glad), their headers and the shaders; a consumer writes
#   find_package(vgi REQUIRED)  target_link_libraries(app PRIVATE vgi::illum)
# (tests/consumer is one, built by the suite's Install.ConsumerBuildsAndRuns).
include(CMakePackageConfigHelpers)
set_target_properties(vgi_core PROPERTIES EXPORT_NAME core)
set_target_properties(vgi_voxelize PROPERTIES EXPORT_NAME voxelize)
set_target_properties(vgi_traverse PROPERTIES EXPORT_NAME traverse)
set_target_properties(vgi_illum PROPERTIES EXPORT_NAME illum)
set_target_properties(vgi_illum_framework PROPERTIES EXPORT_NAME illum_framework)
set_target_properties(vgi_illum_resources PROPERTIES EXPORT_NAME illum_resources)
set_target_properties(vgi_illum_kits PROPERTIES EXPORT_NAME illum_kits)
set_target_properties(vgi_illum_methods PROPERTIES EXPORT_NAME illum_methods)
set_target_properties(vgi_experiments PROPERTIES EXPORT_NAME experiments)
set(_vgi_installed vgi_glad vgi_core vgi_voxelize vgi_traverse vgi_illum_framework vgi_illum_resources
    vgi_illum_kits vgi_illum_methods vgi_illum vgi_experiments vgi)
if(VGI_LEAN_IMAGES)
  list(APPEND _vgi_installed vgi_image_lean)  # vgi_core's image layer in the lean build
endif()
install(TARGETS ${_vgi_installed}
        EXPORT vgiTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(_dir core voxelize traverse illum experiments)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_dir}/ DESTINATION ${VGI_INSTALL_INCLUDEDIR}/${_dir}
          FILES_MATCHING PATTERN "*.h")
endforeach()
# The shared GLSL/C++ kernels are headers of the C++ side too.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/shared/ DESTINATION ${VGI_INSTALL_INCLUDEDIR}/shaders/shared)
install(DIRECTORY ${GLAD_OUT}/include/ DESTINATION ${VGI_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION ${VGI_INSTALL_SHADERDIR})
set(_cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/vgi)
install(EXPORT vgiTargets NAMESPACE vgi:: DESTINATION ${_cfgdir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vgiConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/vgiConfig.cmake INSTALL_DESTINATION ${_cfgdir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vgiConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vgiConfig.cmake ${PROJECT_BINARY_DIR}/vgiConfigVersion.cmake
        DESTINATION ${_cfgdir})
