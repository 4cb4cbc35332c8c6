# The project's targets, made one way. Every library and executable of the
# project links habuffer_options: its warnings and its floating-point rule
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
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:habuffer_options>)
  else()
    add_library(${name} ${ARG_UNPARSED_ARGUMENTS})
    target_link_libraries(${name} PRIVATE $<BUILD_INTERFACE:habuffer_options>)
  endif()
  if(ARG_ALIAS)
    add_library(${ARG_ALIAS} ALIAS ${name})
  endif()
endfunction()

function(habuffer_add_executable name)
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE habuffer_options)
endfunction()
