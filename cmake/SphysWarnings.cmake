# Applies the project's warning flags to a target we compile (never to consumers of the install).
function(sphys_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(SPHYS_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
