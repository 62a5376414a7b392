# Compile through ccache when it is installed (scripts/install-deps.sh installs
# it). CI builds every preset from a clean clone at the same path on every run,
# so without a compiler cache most of its time went to compiling unchanged
# files again. ccache gives back the object the compiler would have made, so
# binaries, images and timings do not change. CCACHE_BASEDIR makes paths
# inside the checkout relative, so clones at other paths share release
# objects too (debug-info builds still key on their directory, as ccache does
# by default, so their file paths stay right).
option(RAYCACHE_CCACHE "Compile through ccache when it is installed" ON)
if(RAYCACHE_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(RAYCACHE_CCACHE_PROGRAM ccache)
  if(RAYCACHE_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER
        ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${CMAKE_SOURCE_DIR} ${RAYCACHE_CCACHE_PROGRAM})
  endif()
endif()
