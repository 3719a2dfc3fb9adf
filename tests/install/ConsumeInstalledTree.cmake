# Install lsdem's build tree into a scratch prefix, build tests/install/consumer against it with
# find_package(lsdem), run the consumer, and run the installed programs with no
# LD_LIBRARY_PATH (their RPATH must find the installed libraries).
# Run by ctest as: cmake -DBUILD_DIR=... -DWORK_DIR=... [-D...] -P ConsumeInstalledTree.cmake
cmake_minimum_required(VERSION 3.20)

foreach(input BUILD_DIR CONSUMER_DIR WORK_DIR GENERATOR CXX_COMPILER CONFIG)
    if(NOT DEFINED ${input})
        message(FATAL_ERROR "ConsumeInstalledTree.cmake: -D${input}=... is missing")
    endif()
endforeach()

# run(STEP OUTPUT_VAR COMMAND args...): run a command without LD_LIBRARY_PATH; stop the test
# with the command's output if it fails.
function(run step outputVar)
    execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH ${ARGN}
        RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
    if(NOT result EQUAL 0)
        message(FATAL_ERROR "${step} failed (${result}):\n${ARGN}\n${output}")
    endif()
    message(STATUS "${step}: ok")
    set(${outputVar} "${output}" PARENT_SCOPE)
endfunction()

function(expectContains step text part)
    string(FIND "${text}" "${part}" at)
    if(at EQUAL -1)
        message(FATAL_ERROR "${step}: expected \"${part}\" in:\n${text}")
    endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})

run("install" out ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix} --config ${CONFIG})
foreach(file bin/lsdem-bake bin/lsdem-grains bin/lsdem-inspect bin/lsdem-pack bin/lsdem-run bin/lsdem-study
        include/lsdem/ls/Bake.h include/lsdem/contact/PairContact.h include/lsdem/run/Checkpoint.h
        share/lsdem/plots/two_spheres.py share/lsdem/plots/plotting.py)
    if(NOT EXISTS ${prefix}/${file})
        message(FATAL_ERROR "install: ${prefix}/${file} is missing")
    endif()
endforeach()

set(consumerBuild ${WORK_DIR}/consumer-build)
set(configureArgs -S ${CONSUMER_DIR} -B ${consumerBuild} -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}")
if(COMPILER_LAUNCHER)
    list(APPEND configureArgs -DCMAKE_CXX_COMPILER_LAUNCHER=${COMPILER_LAUNCHER})
endif()
run("configure the consumer" out ${CMAKE_COMMAND} ${configureArgs})
expectContains("configure the consumer" "${out}" "found in ${prefix}/")
run("build the consumer" out ${CMAKE_COMMAND} --build ${consumerBuild} --config Release)

find_program(consumer lsdem_consumer PATHS ${consumerBuild} ${consumerBuild}/Release
    NO_DEFAULT_PATH REQUIRED)
run("run the consumer" out ${consumer})
message(STATUS "\n${out}")
expectContains("run the consumer" "${out}" "lsdem consumer: ok")

# The installed programs, as a user runs them from the prefix.
run("installed lsdem-bake" out ${prefix}/bin/lsdem-bake --sphere 1 --voxel 0.1
    --node-spacing 0.25 -o ${WORK_DIR}/sphere.vdb)
run("installed lsdem-inspect" out ${prefix}/bin/lsdem-inspect ${WORK_DIR}/sphere.vdb)
expectContains("installed lsdem-inspect" "${out}" "lsdem grain asset")
foreach(program lsdem-grains lsdem-pack lsdem-run lsdem-study)
    run("installed ${program} --help" out ${prefix}/bin/${program} --help)
endforeach()

# The installed Python package (when the build has one), imported from the prefix with no
# LD_LIBRARY_PATH: its RPATH must find the installed libraries too.
# Not in sanitizer builds: a sanitized module cannot be imported by an unsanitized interpreter
# (python/CMakeLists.txt leaves its tests out there too).
file(GLOB installedPackage ${prefix}/lib*/python3*/*-packages/lsdem/__init__.py)
if(installedPackage AND NOT CXX_FLAGS MATCHES "-fsanitize")
    get_filename_component(packageDir ${installedPackage} DIRECTORY)
    get_filename_component(sitePackages ${packageDir} DIRECTORY)
    find_program(python NAMES python3 PATHS /usr/bin NO_DEFAULT_PATH)
    if(NOT python)
        find_program(python NAMES python3 REQUIRED)
    endif()
    # A script file, not -c: the argument list would split the code at its semicolons.
    file(WRITE ${WORK_DIR}/import_lsdem.py
        "import lsdem\nasset = lsdem.load(r'${WORK_DIR}/sphere.vdb')\n"
        "print('lsdem from', lsdem.__file__, len(asset.nodes.positions), 'nodes')\n")
    run("installed Python package" out ${CMAKE_COMMAND} -E env PYTHONPATH=${sitePackages}
        ${python} ${WORK_DIR}/import_lsdem.py)
    expectContains("installed Python package" "${out}" "lsdem from ${packageDir}")
endif()
