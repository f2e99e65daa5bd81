# The git revision goes into every stats sidecar; regenerate it on every build
# so an image always names the code that made it.
add_custom_target(vgi_build_info_gen
  COMMAND ${CMAKE_COMMAND} -DSRC=${PROJECT_SOURCE_DIR} -DVERSION=${PROJECT_VERSION} -DOUT=${PROJECT_BINARY_DIR}/build_info.cpp
          -P ${PROJECT_SOURCE_DIR}/cmake/write_build_info.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/build_info.cpp)
