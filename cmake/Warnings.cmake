# Warning flags applied per target (never globally).
function(raycache_set_warnings target)
  # -Wno-restrict: GCC 12 reports false positives inside std::string (GCC bug 105651).
  # -Wno-missing-field-initializers: designated initializers rely on member defaults.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-restrict
                                           -Wno-missing-field-initializers)
  if(RAYCACHE_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
