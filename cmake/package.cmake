# The installable C++ package: libexemplar.so (every module of src/, whole), the public headers,
# a CMake package (find_package(exemplar CONFIG) -> exemplar::exemplar) and a pkg-config module.
# Third-party libraries stay private to the shared library (the public headers include only the
# standard library), so a consumer needs nothing but the package; its own dependencies are the
# .so's, resolved by the dynamic loader (and by apt for the .deb).
include(CMakePackageConfigHelpers)

set(EXEMPLAR_MODULES exemplar_core exemplar_plugin exemplar_io exemplar_filters exemplar_synth
    exemplar_render exemplar_stylit exemplar_video exemplar_sketch exemplar_animate exemplar_fluid
    exemplar_noisy exemplar_paint exemplar_npr)
# The bundled plugins' code is linked in too (cmake/plugins.cmake): a program using the library
# calls it directly; only the `exemplar` command loads plugins.
get_property(EXEMPLAR_BUNDLED_PLUGINS GLOBAL PROPERTY EXEMPLAR_BUNDLED_PLUGINS)
# The modules' object files, and the modules themselves for their dependencies (the linker
# takes nothing from their archives: the objects already define every symbol).
set(EXEMPLAR_OBJECTS)
foreach(module IN LISTS EXEMPLAR_MODULES)
  list(APPEND EXEMPLAR_OBJECTS $<TARGET_OBJECTS:${module}>)
endforeach()
add_library(exemplar_library SHARED ${EXEMPLAR_OBJECTS})
add_library(exemplar::exemplar ALIAS exemplar_library)
target_link_libraries(exemplar_library PRIVATE ${EXEMPLAR_MODULES})
foreach(plugin IN LISTS EXEMPLAR_BUNDLED_PLUGINS)
  target_link_libraries(exemplar_library PRIVATE ${plugin}_objects)
endforeach()
target_include_directories(exemplar_library PUBLIC
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
target_compile_features(exemplar_library PUBLIC cxx_std_20)
set_target_properties(exemplar_library PROPERTIES
  OUTPUT_NAME exemplar EXPORT_NAME exemplar VERSION ${PROJECT_VERSION}
  SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
  LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)

set(EXEMPLAR_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/exemplar)
install(TARGETS exemplar_library EXPORT exemplarTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/exemplar
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT exemplarTargets NAMESPACE exemplar:: DESTINATION ${EXEMPLAR_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/exemplarConfig.cmake.in
  ${PROJECT_BINARY_DIR}/exemplarConfig.cmake INSTALL_DESTINATION ${EXEMPLAR_CMAKE_DIR})
# 0.x: minor versions may change the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/exemplarConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/exemplarConfig.cmake
              ${PROJECT_BINARY_DIR}/exemplarConfigVersion.cmake
        DESTINATION ${EXEMPLAR_CMAKE_DIR})
# Relocatable: the prefix is found from the .pc file's own folder.
file(RELATIVE_PATH EXEMPLAR_PC_TO_PREFIX "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig"
     "${CMAKE_INSTALL_PREFIX}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/exemplar.pc.in ${PROJECT_BINARY_DIR}/exemplar.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/exemplar.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# `cpack -G DEB` (in the build folder): one .deb with the command, the library, the headers and
# the CMake/pkg-config files under /usr; dpkg-shlibdeps turns the shared objects' needs into
# Depends, so apt resolves them on a fresh Debian.
set(CPACK_PACKAGE_NAME exemplar)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "Transfers the look of a painting, drawing or photo onto renders, segmentations and\n\
 animations by example (StyLit, TCIA, ShipShape): the `exemplar` command, libexemplar.so,\n\
 its C++ headers, CMake package and pkg-config module.")
set(CPACK_PACKAGE_CONTACT "exemplar developers <exemplar-dev@users.noreply.github.com>")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# The Python module is built for one Python version (its ABI) and imports numpy; dpkg-shlibdeps
# sees neither (the extension does not link libpython).
if(EXEMPLAR_PYTHON)
  math(EXPR next_minor "${EXEMPLAR_PYTHON_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3 (>= ${EXEMPLAR_PYTHON_VERSION_MAJOR}.${EXEMPLAR_PYTHON_VERSION_MINOR}), python3 (<< ${EXEMPLAR_PYTHON_VERSION_MAJOR}.${next_minor}), python3-numpy")
  # exemplar.distributed imports dask.distributed only when used.
  set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-distributed")
endif()
include(CPack)
