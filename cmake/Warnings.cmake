# Warning and code-generation flags applied per target (never globally).
function(raycache_set_warnings target)
  # -Wno-missing-field-initializers: designated initializers rely on member defaults.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-missing-field-initializers)
  # -Wno-restrict: GCC 12 reports false positives inside std::string (GCC bug
  # 105651). GCC's alone: clang (the fuzz preset) has no such warning and
  # warns about the unknown option in every batch.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-restrict)
  endif()
  # No fused multiply-adds the source does not write: GCC contracts a * b + c
  # into one FMA in C++ by default wherever the target has FMA (-march=native,
  # the AVX2 and AVX-512 copies of the lane loops), which rounds differently, so images and
  # answers would depend on the machine.
  target_compile_options(${target} PRIVATE -ffp-contract=off)
  # Unity batches (the sanitizer and fuzz presets) include .cpp files into one
  # another, so GCC takes a type from a .cpp's anonymous namespace for a
  # header's and warns; in a .cpp compiled alone the same code is fine.
  get_target_property(unity ${target} UNITY_BUILD)
  if(unity AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -Wno-subobject-linkage)
  endif()
  if(RAYCACHE_NATIVE)
    target_compile_options(${target} PRIVATE -march=native)
  endif()
endfunction()
