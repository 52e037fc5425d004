# The OpenGL 4.5 core loader is generated at build time by Debian's python3-glad.
# /usr/bin/glad runs under the system interpreter; a `python3` earlier on PATH (pyenv, venv)
# may not have the glad module, so the generator is called by its absolute path.

find_program(LUXEL_GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT LUXEL_GLAD_EXECUTABLE)
    find_program(LUXEL_GLAD_EXECUTABLE glad REQUIRED)
endif()

set(_glad_dir ${PROJECT_BINARY_DIR}/generated/glad)
set(_glad_outputs ${_glad_dir}/src/gl.c ${_glad_dir}/include/glad/gl.h
                  ${_glad_dir}/include/KHR/khrplatform.h)
# KHR_debug routes driver messages to our log; the rest of GL 4.5 core is enough for luxel.
add_custom_command(
    OUTPUT ${_glad_outputs}
    COMMAND ${LUXEL_GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=4.5
            --extensions GL_KHR_debug --out-path ${_glad_dir} c
    COMMENT "Generating the OpenGL 4.5 core loader with glad"
    VERBATIM)

add_library(luxel_glad STATIC ${_glad_outputs})
target_include_directories(luxel_glad SYSTEM PUBLIC ${_glad_dir}/include)
set_target_properties(luxel_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(luxel_glad PUBLIC ${CMAKE_DL_LIBS})
add_library(luxel::glad ALIAS luxel_glad)
