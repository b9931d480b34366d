# Warnings every target of ours compiles with.
add_library(sm2_warnings INTERFACE)
target_compile_options(sm2_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual
  -Wimplicit-fallthrough -Wmissing-declarations)
if(SM2_WERROR)
  target_compile_options(sm2_warnings INTERFACE -Werror)
endif()
