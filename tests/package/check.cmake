# The installed package, as a user gets it (ctest: package_install_and_consume):
#   1. cmake --install the build tree into a fresh prefix under WORK_DIR;
#   2. the files a user looks for are there (headers, config, version file, .pc, modules, sm2, docs);
#   3. a consumer project (tests/package/consumer) configures with find_package(sm2emu), builds,
#      installs into the prefix and runs: it assembles, replays a stream with heredoc shaders,
#      writes and reads a PNG through the image module found beside the relocated install;
#   4. the same program compiled by hand with `pkg-config --cflags --libs sm2emu`;
#   5. the installed sm2 runs.
# cmake -DBUILD_DIR=... -DWORK_DIR=... -DCONSUMER_DIR=... -DCXX=... -DGENERATOR=... -DEXTRA_FLAGS=... -P check.cmake
cmake_minimum_required(VERSION 3.20)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

function(expect haystack needle)
  string(FIND "${haystack}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "expected '${needle}' in:\n${haystack}")
  endif()
endfunction()

set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

include(GNUInstallDirs)  # the same relative folders as the build's (lib, include, bin, share/doc)
file(GLOB_RECURSE config_files RELATIVE ${prefix} ${prefix}/*sm2emuConfig*.cmake ${prefix}/*sm2emu.pc)
list(LENGTH config_files n)
if(NOT n EQUAL 3)
  message(FATAL_ERROR "expected sm2emuConfig.cmake, sm2emuConfigVersion.cmake and sm2emu.pc, got: ${config_files}")
endif()
foreach(f include/sm2/runtime/stream_assembler.h include/sm2/runtime/replay.h include/sm2/assembler/assembler.h
          include/sm2/isa/validator.h include/sm2/emu/engine.h bin/sm2)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
file(GLOB_RECURSE modules ${prefix}/*/sm2emu/sm2emu_image_io.so)
file(GLOB_RECURSE docs ${prefix}/share/doc/*/command-stream.md ${prefix}/share/doc/*/README.md)
if(NOT modules OR NOT docs)
  message(FATAL_ERROR "the image module or the docs are missing: '${modules}' '${docs}'")
endif()
get_filename_component(module_dir ${modules} DIRECTORY)

# find_package
run(${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${WORK_DIR}/consumer-build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_CXX_FLAGS=${EXTRA_FLAGS} -DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_INSTALL_PREFIX=${prefix} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/consumer-build)
run(${CMAKE_COMMAND} --install ${WORK_DIR}/consumer-build)
run(${prefix}/bin/consumer ${WORK_DIR}/frames)
message(STATUS "consumer (find_package):\n${run_output}")
expect("${run_output}" "assembled 5 tokens, version 0xFFFF0200")
expect("${run_output}" "replayed 15 calls, 1 frame(s), 64 pixels shaded")
expect("${run_output}" "frame 8x8, pixel (4,4) = 1.00000 0.50196 0.00000 1.00000")
expect("${run_output}" "image module: ${module_dir}/sm2emu_image_io.so")  # the relocated install's

# pkg-config, by hand
find_program(PKG_CONFIG NAMES pkg-config pkgconf)
if(PKG_CONFIG)
  file(GLOB_RECURSE pc ${prefix}/*/sm2emu.pc)
  get_filename_component(pc_dir ${pc} DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} ${pc_dir})
  run(${PKG_CONFIG} --define-prefix --cflags --libs sm2emu)
  string(STRIP "${run_output}" flags)
  expect("${flags}" "-I${prefix}/include")
  separate_arguments(flags UNIX_COMMAND "${flags}")
  separate_arguments(extra UNIX_COMMAND "${EXTRA_FLAGS}")
  run(${CXX} -std=c++20 ${extra} ${CONSUMER_DIR}/main.cpp ${flags} -o ${prefix}/bin/consumer_pc)
  run(${prefix}/bin/consumer_pc ${WORK_DIR}/frames_pc)
  expect("${run_output}" "frame 8x8, pixel (4,4) = 1.00000 0.50196 0.00000 1.00000")
endif()

# the installed tool
run(${prefix}/bin/sm2 --version)
expect("${run_output}" "sm2emu 0.1.0")
file(REMOVE_RECURSE ${WORK_DIR})
