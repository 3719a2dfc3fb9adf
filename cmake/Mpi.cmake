# Optional MPI (Debian: libopenmpi-dev and openmpi-bin, see scripts/install-deps.sh):
# `mpirun -n N lsdem-study ...` spreads a study's independent runs over the ranks. Found by
# itself; a machine without MPI still builds everything, and lsdem-study runs in one process.
#   -DLSDEM_MPI=AUTO (default): with MPI if found;  ON: MPI required;  OFF: never.
# AUTO is asked again at every configure, so installing MPI later needs no cache surgery.
set(LSDEM_MPI AUTO CACHE STRING "Spread lsdem-study's runs over MPI ranks: AUTO (if found), ON, OFF")
set_property(CACHE LSDEM_MPI PROPERTY STRINGS AUTO ON OFF)

set(LSDEM_WITH_MPI OFF)
if(NOT LSDEM_MPI STREQUAL "OFF")
    find_package(MPI COMPONENTS CXX QUIET)
    if(MPI_CXX_FOUND)
        set(LSDEM_WITH_MPI ON)
        message(STATUS "lsdem: MPI ${MPI_CXX_VERSION} found (${MPIEXEC_EXECUTABLE}): "
                       "lsdem-study spreads its runs over mpirun's ranks")
    elseif(LSDEM_MPI STREQUAL "ON")
        message(FATAL_ERROR "LSDEM_MPI is ON but no MPI for C++ was found: install "
                            "libopenmpi-dev and openmpi-bin (scripts/install-deps.sh), or "
                            "configure with -DLSDEM_MPI=AUTO or OFF")
    else()
        message(STATUS "lsdem: no MPI found (libopenmpi-dev): lsdem-study runs in one process")
    endif()
endif()
