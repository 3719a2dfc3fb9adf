# All dependencies come from Debian packages (see scripts/install-deps.sh).

# Debian's OpenVDB ships a find module rather than a package config file; lsdemConfig.cmake
# points its consumers here too.
set(LSDEM_OPENVDB_MODULE_DIR "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB"
    CACHE PATH "Folder holding OpenVDB's FindOpenVDB.cmake")
list(APPEND CMAKE_MODULE_PATH ${LSDEM_OPENVDB_MODULE_DIR})
find_package(OpenVDB REQUIRED COMPONENTS openvdb)
# FindOpenVDB sets BUILD_SHARED_LIBS ON in our scope; drop it so our option of that name decides.
unset(BUILD_SHARED_LIBS)
find_package(Imath CONFIG REQUIRED)
# TBB::tbb comes with OpenVDB's FindOpenVDB (its own FindTBB); a second find_package clashes.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(assimp CONFIG REQUIRED)
find_package(CGAL CONFIG REQUIRED)
find_package(PNG REQUIRED)
find_package(Threads REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(OpenSSL REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
# Optional: MPI for lsdem-study (cmake/Mpi.cmake).
include(${CMAKE_CURRENT_LIST_DIR}/Mpi.cmake)
