# The project's targets, made one way. Every library and executable of the
# project links habuffer_build_flags: its warnings and its floating-point rule
# -ffp-contract=off, on which the CPU path's bit identity with the GPU path
# rests (no fused multiply-add in one and not the other). A target made with
# these functions cannot lose them; the test build.fp_contract checks every
# compiled file of the build (compile_commands.json) for the flag, so a
# target made any other way is caught too.
#
#   habuffer_add_library(NAME [STATIC|INTERFACE] SOURCES... [ALIAS habuffer::x])
#   habuffer_add_executable(NAME SOURCES...)
#
# The options are linked privately and only inside the build tree
# ($<BUILD_INTERFACE:...>): an installed library carries none of them to a host.

function(habuffer_add_library name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "STATIC;INTERFACE" "ALIAS" "")
  if(ARG_INTERFACE)
    add_library(${name} INTERFACE ${ARG_UNPARSED_ARGUMENTS})
  elseif(ARG_STATIC)
    add_library(${name} STATIC ${ARG_UNPARSED_ARGUMENTS})
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:habuffer_build_flags>)
  else()
    add_library(${name} ${ARG_UNPARSED_ARGUMENTS})
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:habuffer_build_flags>)
  endif()
  if(ARG_ALIAS)
    add_library(${ARG_ALIAS} ALIAS ${name})
  endif()
endfunction()

function(habuffer_add_executable name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE habuffer_build_flags)
endfunction()

# A part: one concern of an umbrella library (habuffer::core, habuffer::gl),
# a folder holding
#   include/   its public headers (installed with the umbrella),
#   internal/  headers the project's other parts may include, never installed,
#   src/       its sources and private headers.
# An OBJECT library (INTERFACE when it has no sources) that sees only its own
# folders and those of its DEPS: an include of a part it did not declare does
# not compile. The umbrella links every part of its name (habuffer_umbrella)
# and so holds their objects; docs/architecture.md draws the graph and
# scripts/check_layers.py checks every include runs down its order.
#
#   habuffer_add_part(NAME OF core|gl [DIR folder] [SOURCES...] [DEPS...] [PRIVATE_DEPS...])
#
# DIR (default: the current folder) is the part's folder; SOURCES are
# relative to it.
function(habuffer_add_part name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "OF;DIR" "SOURCES;DEPS;PRIVATE_DEPS")
  set(dir ${CMAKE_CURRENT_SOURCE_DIR})
  if(ARG_DIR)
    set(dir ${CMAKE_CURRENT_SOURCE_DIR}/${ARG_DIR})
    set(sources)
    foreach(f IN LISTS ARG_SOURCES)
      if(IS_ABSOLUTE ${f})
        list(APPEND sources ${f})
      else()
        list(APPEND sources ${dir}/${f})
      endif()
    endforeach()
    set(ARG_SOURCES ${sources})
  endif()
  if(ARG_SOURCES)
    add_library(${name} OBJECT ${ARG_SOURCES})
    set(scope PUBLIC)
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:habuffer_build_flags> ${ARG_PRIVATE_DEPS})
    if(BUILD_SHARED_LIBS)
      set_target_properties(${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    endif()
    if(IS_DIRECTORY ${dir}/src)
      target_include_directories(${name} PRIVATE ${dir}/src)
    endif()
  else()
    add_library(${name} INTERFACE)
    set(scope INTERFACE)
  endif()
  foreach(sub include internal)
    if(IS_DIRECTORY ${dir}/${sub})
      target_include_directories(${name} ${scope} $<BUILD_INTERFACE:${dir}/${sub}>)
    endif()
  endforeach()
  target_link_libraries(${name} ${scope} ${ARG_DEPS})
  target_compile_features(${name} ${scope} cxx_std_20)
  set_property(GLOBAL APPEND PROPERTY HABUFFER_PARTS_${ARG_OF} ${name})
  if(IS_DIRECTORY ${dir}/include)
    set_property(GLOBAL APPEND PROPERTY HABUFFER_PUBLIC_INCLUDES_${ARG_OF} ${dir}/include)
  endif()
endfunction()

# A path's library (core, gl, vk): the parts in the folders PARTS of the
# calling folder (added here), the library `name` as habuffer::`of`, its
# one-include header folder include/ above every part, and every part
# declared OF `of` linked in (habuffer_umbrella). The caller adds the
# library's own dependencies.
function(habuffer_path_library name)
  cmake_parse_arguments(PARSE_ARGV 1 ARG "" "OF" "PARTS")
  foreach(part IN LISTS ARG_PARTS)
    add_subdirectory(${part})
  endforeach()
  habuffer_add_library(${name} ALIAS habuffer::${ARG_OF})
  set_target_properties(${name} PROPERTIES EXPORT_NAME ${ARG_OF})
  target_compile_features(${name} PUBLIC cxx_std_20)
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
                                            $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  set_property(GLOBAL APPEND PROPERTY HABUFFER_PUBLIC_INCLUDES_${ARG_OF} ${CMAKE_CURRENT_SOURCE_DIR}/include)
  habuffer_umbrella(${name} ${ARG_OF})
endfunction()

# The umbrella `name` links every part declared OF `of`, at the end of
# configuration (parts come from core/, gl/ and each technique's folder).
function(habuffer_umbrella name of)
  cmake_language(EVAL CODE "
    cmake_language(DEFER DIRECTORY [[${PROJECT_SOURCE_DIR}]] CALL _habuffer_link_parts [[${name}]] [[${of}]])")
endfunction()

function(_habuffer_link_parts name of)
  get_property(parts GLOBAL PROPERTY HABUFFER_PARTS_${of})
  foreach(p IN LISTS parts)
    target_link_libraries(${name} PUBLIC $<BUILD_INTERFACE:${p}>)
  endforeach()
endfunction()
