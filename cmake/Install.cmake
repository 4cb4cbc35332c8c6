# Install rules: the libraries a host links (habuffer::common, ::offsets, ::core and,
# with the GL path, ::gl, with the Vulkan path ::vk), their headers (the shared C++/GLSL sources
# included), the host GLSL files, the CMake package habufferConfig.cmake
# with its version file, and pkg-config files habuffer-core.pc,
# habuffer-gl.pc and habuffer-vk.pc, and the license (MIT).
include(CMakePackageConfigHelpers)

set(_habuffer_targets habuffer_common habuffer_offsets habuffer_core)
set(_habuffer_components offsets core)
if(HABUFFER_WITH_GL)
  list(APPEND _habuffer_targets habuffer_gl)
  list(APPEND _habuffer_components gl)
endif()
if(HABUFFER_VULKAN)
  list(APPEND _habuffer_targets habuffer_vk)
  list(APPEND _habuffer_components vk)
endif()
get_target_property(_habuffer_type habuffer_core TYPE)

install(TARGETS ${_habuffer_targets} EXPORT habufferTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The technique folders keep their sources beside their headers: not installed.
# The public headers: every part's include/ folder (internal/ and src/ stay
# behind), the parts of habuffer::core first.
get_property(_habuffer_core_includes GLOBAL PROPERTY HABUFFER_PUBLIC_INCLUDES_core)
foreach(_dir common/include offsets/include ${_habuffer_core_includes})
  install(DIRECTORY ${_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})  # MIT; named by the CMake and pkg-config packages
if(HABUFFER_WITH_GL)
  get_property(_habuffer_gl_includes GLOBAL PROPERTY HABUFFER_PUBLIC_INCLUDES_gl)
  foreach(_dir IN LISTS _habuffer_gl_includes)
    install(DIRECTORY ${_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endforeach()
  install(DIRECTORY ${HABUFFER_GLSL_DIR}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/habuffer/glsl PATTERN stamp EXCLUDE)
endif()
if(HABUFFER_VULKAN)
  get_property(_habuffer_vk_includes GLOBAL PROPERTY HABUFFER_PUBLIC_INCLUDES_vk)
  foreach(_dir IN LISTS _habuffer_vk_includes)
    install(DIRECTORY ${_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endforeach()
endif()

set(HABUFFER_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/habuffer)
install(EXPORT habufferTargets NAMESPACE habuffer:: DESTINATION ${HABUFFER_CMAKE_DIR})
# What the package's config must find for a consumer: static libraries carry
# their private dependencies (oneTBB) into the consumer's link.
set(HABUFFER_PACKAGE_STATIC OFF)
if(_habuffer_type STREQUAL "STATIC_LIBRARY")
  set(HABUFFER_PACKAGE_STATIC ON)
endif()
set(HABUFFER_PACKAGE_WITH_TBB ${HABUFFER_WITH_TBB})
set(HABUFFER_PACKAGE_COMPONENTS ${_habuffer_components})
configure_package_config_file(cmake/habufferConfig.cmake.in ${PROJECT_BINARY_DIR}/habufferConfig.cmake
                              INSTALL_DESTINATION ${HABUFFER_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_INCLUDEDIR CMAKE_INSTALL_DATADIR CMAKE_INSTALL_DOCDIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/habufferConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/habufferConfig.cmake ${PROJECT_BINARY_DIR}/habufferConfigVersion.cmake
        DESTINATION ${HABUFFER_CMAKE_DIR})

# pkg-config: for a static build the dependencies are public (a consumer that
# does not pass --static still links what the archives need).
if(HABUFFER_PACKAGE_STATIC)
  set(_pc_requires_field "Requires")
else()
  set(_pc_requires_field "Requires.private")
endif()
set(_pc_core_requires "glm")
if(HABUFFER_WITH_TBB)
  string(APPEND _pc_core_requires ", tbb")
endif()
# Relocatable: the prefix is found from the .pc file's own directory, so a
# `cmake --install --prefix` anywhere gives working files.
file(RELATIVE_PATH HABUFFER_PC_PREFIX_FROM_PCDIR /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
# Without its trailing slash: ${prefix}/share, not ${prefix}//share (a glsldir of "../..//share").
string(REGEX REPLACE "/+$" "" HABUFFER_PC_PREFIX_FROM_PCDIR "${HABUFFER_PC_PREFIX_FROM_PCDIR}")
set(HABUFFER_PC_CORE_REQUIRES "${_pc_requires_field}: ${_pc_core_requires}")
set(HABUFFER_PC_GL_REQUIRES "Requires: habuffer-core = ${PROJECT_VERSION}, epoxy")
configure_file(cmake/habuffer-core.pc.in ${PROJECT_BINARY_DIR}/habuffer-core.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/habuffer-core.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
# The Vulkan path: the loader, and glslang's libraries (its run-time
# compiler; Debian's glslang.pc leaves out the default resource limits).
if(HABUFFER_PACKAGE_STATIC)
  set(HABUFFER_PC_VK_REQUIRES "Requires: habuffer-gl = ${PROJECT_VERSION}, vulkan, glslang, spirv")
  set(HABUFFER_PC_VK_LIBS "-lhabuffer_vk -lglslang-default-resource-limits")
else()
  # Debian's glslang is static: libhabuffer_vk.so holds what it uses.
  set(HABUFFER_PC_VK_REQUIRES "Requires: habuffer-gl = ${PROJECT_VERSION}, vulkan")
  set(HABUFFER_PC_VK_LIBS "-lhabuffer_vk")
endif()
if(HABUFFER_VULKAN)
  configure_file(cmake/habuffer-vk.pc.in ${PROJECT_BINARY_DIR}/habuffer-vk.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/habuffer-vk.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
if(HABUFFER_WITH_GL)
  configure_file(cmake/habuffer-gl.pc.in ${PROJECT_BINARY_DIR}/habuffer-gl.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/habuffer-gl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endif()
