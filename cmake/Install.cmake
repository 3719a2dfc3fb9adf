# Installation: `cmake --install build --prefix P` puts the programs in P/bin, the libraries in
# P/lib, the headers in P/include/lsdem, the plot scripts in P/share/lsdem/plots and a CMake
# package in P/lib/cmake/lsdem, so that consumers write find_package(lsdem) and link lsdem::ls.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Installed programs find lsdem's libraries relative to themselves (bin/../lib), so the prefix
# can go anywhere without LD_LIBRARY_PATH; the libraries find each other next to themselves.
# System libraries (OpenVDB, TBB, ...) need no RPATH.
file(RELATIVE_PATH LSDEM_BIN_TO_LIB ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
set(CMAKE_INSTALL_RPATH "$ORIGIN/${LSDEM_BIN_TO_LIB}")

set(LSDEM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/lsdem)

# lsdem_install_library(TARGET NAME [HEADERS DIR]): make TARGET part of the installed package
# as lsdem::NAME (and the same alias in the build tree), with the headers in DIR (a folder
# holding lsdem/...) if given.
function(lsdem_install_library target name)
    cmake_parse_arguments(ARG "" "HEADERS" "" ${ARGN})
    # Before 1.0 every minor version may break the ABI, so it is part of the soname.
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} INSTALL_RPATH "$ORIGIN"
        VERSION ${PROJECT_VERSION}
        SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
    add_library(lsdem::${name} ALIAS ${target})
    install(TARGETS ${target} EXPORT lsdemTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    if(ARG_HEADERS)
        install(DIRECTORY ${ARG_HEADERS}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
    endif()
endfunction()

# lsdem_install_package(): the exported targets, lsdemConfig.cmake and its version file. Call
# once, after every lsdem_install_library.
function(lsdem_install_package)
    install(EXPORT lsdemTargets NAMESPACE lsdem:: DESTINATION ${LSDEM_INSTALL_CMAKEDIR})
    configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lsdemConfig.cmake.in
        ${PROJECT_BINARY_DIR}/lsdemConfig.cmake
        INSTALL_DESTINATION ${LSDEM_INSTALL_CMAKEDIR})
    # Before 1.0 a minor version may change the interfaces (as the soname says).
    write_basic_package_version_file(${PROJECT_BINARY_DIR}/lsdemConfigVersion.cmake
        COMPATIBILITY SameMinorVersion)
    install(FILES ${PROJECT_BINARY_DIR}/lsdemConfig.cmake
        ${PROJECT_BINARY_DIR}/lsdemConfigVersion.cmake
        DESTINATION ${LSDEM_INSTALL_CMAKEDIR})
endfunction()
