# Plugins (docs/architecture.md, "Plugins"): the code that uses a heavy third-party library,
# built as a CMake MODULE that `exemplar` loads with dlopen on first use (src/plugin), so that
# commands that do not need the library do not map it.
#
# exemplar_add_plugin(<name> SOURCES ... LIBS ... [BUNDLED]) makes
#   <name>_objects  the compiled sources (an OBJECT library, hidden visibility but for the entry
#                   point), with LIBS as its usage requirements;
#   <name>          lib<name>.so, next to the `exemplar` executable in the build tree and in
#                   ${EXEMPLAR_INSTALL_PLUGINDIR} when installed.
# BUNDLED plugins are also linked into libexemplar.so and the Python module (their modules find
# the entry point through a weak symbol and call it directly); the others are always loaded.
set(EXEMPLAR_INSTALL_PLUGINDIR ${CMAKE_INSTALL_LIBDIR}/exemplar)
# The same folder as seen from the installed executable (the loader looks there).
cmake_path(RELATIVE_PATH CMAKE_INSTALL_FULL_LIBDIR BASE_DIRECTORY "${CMAKE_INSTALL_FULL_BINDIR}"
           OUTPUT_VARIABLE EXEMPLAR_LIBDIR_FROM_BINDIR)
cmake_path(APPEND EXEMPLAR_LIBDIR_FROM_BINDIR exemplar OUTPUT_VARIABLE EXEMPLAR_PLUGINDIR_FROM_BINDIR)

function(exemplar_add_plugin name)
  cmake_parse_arguments(ARG "BUNDLED" "" "SOURCES;LIBS" ${ARGN})
  add_library(${name}_objects OBJECT ${ARG_SOURCES})
  set_target_properties(${name}_objects PROPERTIES
    CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  target_link_libraries(${name}_objects PUBLIC ${ARG_LIBS} PRIVATE exemplar::warnings)
  # Interface headers may use exemplar's public types (Status); plugins link no exemplar library.
  target_include_directories(${name}_objects PRIVATE ${PROJECT_SOURCE_DIR}/include
                             ${PROJECT_SOURCE_DIR}/src/plugin)
  add_library(${name} MODULE)
  target_link_libraries(${name} PRIVATE ${name}_objects)
  set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR})
  install(TARGETS ${name} LIBRARY DESTINATION ${EXEMPLAR_INSTALL_PLUGINDIR})
  set_property(GLOBAL APPEND PROPERTY EXEMPLAR_PLUGINS ${name})
  if(ARG_BUNDLED)
    set_property(GLOBAL APPEND PROPERTY EXEMPLAR_BUNDLED_PLUGINS ${name})
  endif()
endfunction()
