# Generates the GL 4.5 core loader with python3-glad at build time. Debian's
# python3-glad lives in the system interpreter, which may not be the python3 on
# PATH (pyenv, venvs), so look for an interpreter that can import it.
set(_glad_python "")
foreach(_cand /usr/bin/python3 python3)
  find_program(_py NAMES ${_cand} NO_CACHE)
  if(_py)
    execute_process(COMMAND ${_py} -c "import glad" RESULT_VARIABLE _rc OUTPUT_QUIET ERROR_QUIET)
    if(_rc EQUAL 0)
      set(_glad_python ${_py})
      break()
    endif()
  endif()
  unset(_py)
endforeach()
if(NOT _glad_python)
  message(FATAL_ERROR "No python3 with the 'glad' module found: run scripts/setup.sh (installs python3-glad)")
endif()

set(GLAD_OUT ${PROJECT_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${_glad_python} -m glad --api gl:core=4.5 --extensions GL_KHR_debug
          --out-path ${GLAD_OUT} --reproducible --quiet c
  COMMENT "Generating the GL 4.5 core loader (glad)"
  VERBATIM)
add_library(vgi_glad STATIC ${GLAD_OUT}/src/gl.c)
target_include_directories(vgi_glad PUBLIC $<BUILD_INTERFACE:${GLAD_OUT}/include>
                                           $<INSTALL_INTERFACE:${VGI_INSTALL_INCLUDEDIR}>)
set_target_properties(vgi_glad PROPERTIES EXPORT_NAME glad)
set_target_properties(vgi_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
