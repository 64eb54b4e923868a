# umbra_embed_glsl(TARGET lib GLSL file HEADER name.hpp NAMESPACE ns CONSTANT kName): the
# GLSL twin of a physics library, embedded as a string constant `ns::kName` in a generated
# header `name.hpp` that the INTERFACE library `lib` puts on the include path (the render
# pass compiles it). A change of the file reconfigures.
function(umbra_embed_glsl)
  cmake_parse_arguments(ARG "" "TARGET;GLSL;HEADER;NAMESPACE;CONSTANT" "" ${ARGN})
  set(path ${CMAKE_CURRENT_SOURCE_DIR}/${ARG_GLSL})
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${path})
  file(READ ${path} UMBRA_GLSL_SOURCE)
  file(RELATIVE_PATH UMBRA_GLSL_FILE ${PROJECT_SOURCE_DIR} ${path})
  set(UMBRA_GLSL_NAMESPACE ${ARG_NAMESPACE})
  set(UMBRA_GLSL_CONSTANT ${ARG_CONSTANT})
  configure_file(${PROJECT_SOURCE_DIR}/cmake/EmbeddedGlsl.hpp.in ${CMAKE_CURRENT_BINARY_DIR}/generated/${ARG_HEADER} @ONLY)
  add_library(${ARG_TARGET} INTERFACE)
  target_include_directories(${ARG_TARGET} INTERFACE ${CMAKE_CURRENT_BINARY_DIR}/generated)
endfunction()
