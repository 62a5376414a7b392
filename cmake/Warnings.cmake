# Warning and code-generation flags applied per target (never globally).
function(raycache_set_warnings target)
  # -Wno-restrict: GCC 12 reports false positives inside std::string (GCC bug 105651).
  # -Wno-missing-field-initializers: designated initializers rely on member defaults.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-restrict
                                           -Wno-missing-field-initializers)
  # No fused multiply-adds the source does not write: GCC contracts a * b + c
  # into one FMA in C++ by default wherever the target has FMA (-march=native,
  # the grids' AVX2 clones), which rounds differently, so images and
  # answers would depend on the machine.
  target_compile_options(${target} PRIVATE -ffp-contract=off)
  if(RAYCACHE_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
