# Fails when a native kernel object (emu/CMakeLists.txt: kernels.cpp once per x86-64 level)
# defines a weak symbol, i.e. an inline function clang left out of line. Each level's object
# would define it, the linker would keep one, and the other levels' kernels would call that
# level's code: slower, or an illegal instruction on a CPU without its instructions.
#   cmake -DNM=... -DOBJECT=... -P check_native_kernels.cmake
execute_process(COMMAND ${NM} --defined-only ${OBJECT} OUTPUT_VARIABLE symbols RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "${NM} could not read ${OBJECT}")
endif()
string(REGEX MATCHALL "[^\n]* [WVu] [^\n]*" weak "${symbols}")
if(weak)
  list(JOIN weak "\n  " listed)
  message(FATAL_ERROR "${OBJECT} defines weak symbols (inline functions left out of line), which the "
                      "native kernels' levels would share:\n  ${listed}")
endif()
