# What `cmake --install build --prefix P` puts under P, and the Debian packages `cpack -G DEB` makes of it
# (issue 37; doc/install.md). The apps and the public libraries install themselves (gridtopo_app, gridtopo_library
# in cmake/gridtopo.cmake); here: the data, the INI files, the CMake package and CPack.
include(CMakePackageConfigHelpers)

# The apps look for the shipped data in BIN/../share/gridtopo/datasets (gridtopo::dataDirs in libs/core), so the
# data goes there: the prefix's share/ must stay beside its bin/.
if(NOT CMAKE_INSTALL_BINDIR STREQUAL "bin" OR NOT CMAKE_INSTALL_DATADIR STREQUAL "share")
  message(WARNING "CMAKE_INSTALL_BINDIR=${CMAKE_INSTALL_BINDIR}, CMAKE_INSTALL_DATADIR=${CMAKE_INSTALL_DATADIR}: the "
                  "installed apps look for their data in bin/../share/gridtopo/datasets; set GRIDTOPO_DATA_DIR")
endif()
set(GRIDTOPO_INSTALL_SHARE_DIR ${CMAKE_INSTALL_DATADIR}/gridtopo)
# The data the apps use by default: the place models (gridtopo-topology's and gridtopo-map's default -m), with the
# data's attribution and licences.
install(FILES ${CMAKE_SOURCE_DIR}/datasets/models/places_model.yml
              ${CMAKE_SOURCE_DIR}/datasets/models/places_model_fr101_fr52.yml
        DESTINATION ${GRIDTOPO_INSTALL_SHARE_DIR}/datasets/models COMPONENT runtime)
install(FILES ${CMAKE_SOURCE_DIR}/datasets/README.md DESTINATION ${GRIDTOPO_INSTALL_SHARE_DIR}/datasets
        COMPONENT runtime)
# The commented INI files: every option of every app, and the example RUN.ini files.
install(DIRECTORY ${CMAKE_SOURCE_DIR}/config-ini/ DESTINATION ${GRIDTOPO_INSTALL_SHARE_DIR}/config-ini
        COMPONENT runtime)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT runtime)

# find_package(gridtopo): the targets gridtopo::core, ::io, ::places, ::topology, ::slam, ::mapping (the same names as
# inside the tree) and their dependencies, found again by gridtopoConfig.cmake.
set(GRIDTOPO_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gridtopo)
install(EXPORT gridtopoTargets NAMESPACE gridtopo:: DESTINATION ${GRIDTOPO_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/gridtopoConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/gridtopoConfig.cmake
                              INSTALL_DESTINATION ${GRIDTOPO_CMAKE_DIR}
                              PATH_VARS GRIDTOPO_INSTALL_SHARE_DIR)
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/gridtopoConfigVersion.cmake VERSION ${PROJECT_VERSION}
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/gridtopoConfig.cmake ${CMAKE_BINARY_DIR}/gridtopoConfigVersion.cmake
        DESTINATION ${GRIDTOPO_CMAKE_DIR} COMPONENT dev)

# CPack: `cd build && cpack -G DEB` makes two packages for Debian 12:
#   gridtopo      the apps, the shared libraries, the data and INI files; Depends computed by dpkg-shlibdeps from
#                 the binaries (libmrpt-*2.5, libopencv-*406, libceres3, ...);
#   gridtopo-dev  the headers and the CMake package; Depends on gridtopo and the -dev packages find_package(gridtopo)
#                 needs (the specific libmrpt-*-dev, never the libmrpt-dev metapackage).
set(CPACK_PACKAGE_NAME gridtopo)
set(CPACK_PACKAGE_VENDOR "gridtopo")
set(CPACK_PACKAGE_CONTACT "gridtopo maintainers <gridtopo@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "RBPF grid SLAM and room/corridor/doorway topology on MRPT")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME gridtopo)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)   # a shlibs file and ldconfig triggers for our libraries
# One string each (a list would put ';' into the control file): the synopsis line, then the extended description.
set(CPACK_DEBIAN_RUNTIME_DESCRIPTION "RBPF grid SLAM and room/corridor/doorway topology on MRPT
The apps gridtopo-slam, gridtopo-topology, gridtopo-map, ... and gridtopo-gui, their shared libraries, the shipped
place model and the commented INI files (/usr/share/gridtopo).")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME gridtopo-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "gridtopo (= ${PROJECT_VERSION}), libmrpt-slam-dev, libmrpt-maps-dev, libmrpt-obs-dev, libmrpt-graphs-dev, \
libmrpt-config-dev, libmrpt-math-dev, libmrpt-poses-dev, libmrpt-serialization-dev, libmrpt-io-dev, \
libmrpt-system-dev, libopencv-dev, libopencv-contrib-dev, libeigen3-dev, libceres-dev, nlohmann-json3-dev, \
libtclap-dev, zlib1g-dev")
set(CPACK_DEBIAN_DEV_DESCRIPTION "gridtopo: headers and CMake package
find_package(gridtopo) gives the targets gridtopo::slam, gridtopo::topology, gridtopo::mapping, gridtopo::places,
gridtopo::io and gridtopo::core.")
include(CPack)
