# softsub_module(NAME SOURCES... DEPS ...): one static library per module with the
# project's warning set. Only the listed DEPS are linked, so a module that includes a
# header from a module it may not use fails to build (include paths come from links).
function(softsub_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion)
  if(SOFTSUB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

function(softsub_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(softsub_${name} STATIC ${M_SOURCES})
  add_library(softsub::${name} ALIAS softsub_${name})
  # Headers are included as "<module>/<file>.h" from src/, but only through the
  # module's own target: src/<module> is exported one level up via a per-module
  # include folder so that an unlinked module's headers are not visible.
  target_include_directories(softsub_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/include/${name}>)
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/include/${name})
  if(NOT EXISTS ${CMAKE_BINARY_DIR}/include/${name}/${name})
    file(CREATE_LINK ${CMAKE_SOURCE_DIR}/src/${name} ${CMAKE_BINARY_DIR}/include/${name}/${name} SYMBOLIC)
  endif()
  target_link_libraries(softsub_${name} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  softsub_warnings(softsub_${name})
endfunction()
