# umbra_add_parts(dir...): add each listed sub-folder that has a CMakeLists.txt, so that
# parts can land one at a time without editing their parent.
function(umbra_add_parts)
  foreach(part IN LISTS ARGN)
    if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/${part}/CMakeLists.txt")
      add_subdirectory(${part})
    endif()
  endforeach()
endfunction()
