# All dependencies come from Debian packages (see scripts/install-deps.sh).
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED COMPONENTS openvdb)
find_package(Imath CONFIG REQUIRED)
# TBB::tbb comes with OpenVDB's FindOpenVDB (its own FindTBB); a second find_package clashes.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(assimp CONFIG REQUIRED)
find_package(CGAL CONFIG REQUIRED)
find_package(PNG REQUIRED)
find_package(Threads REQUIRED)
find_package(tomlplusplus CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
