# Compile through ccache when it is installed (scripts/install-deps.sh installs
# it). CI builds every preset from a clean clone, so without a compiler cache
# most of its time went to compiling unchanged files again. ccache gives back
# the object the compiler would have made, so binaries, images and timings do
# not change. CCACHE_BASEDIR makes paths inside the checkout relative, so
# clones at other paths share objects. Builds with debug information (the
# sanitizer and fuzz presets) write the checkout's path into it, and ccache
# then keys on the directory by default (hash_dir), so a clone at another
# path missed on every one of them: those builds map the checkout to "." in
# their debug information (-fdebug-prefix-map), which makes it the same in
# every clone, and tell ccache not to key on the directory (CCACHE_NOHASHDIR).
# Sanitizer reports then name files relative to the checkout.
option(RAYCACHE_CCACHE "Compile through ccache when it is installed" ON)
if(RAYCACHE_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(RAYCACHE_CCACHE_PROGRAM ccache)
  if(RAYCACHE_CCACHE_PROGRAM)
    set(CMAKE_CXX_COMPILER_LAUNCHER
        ${CMAKE_COMMAND} -E env CCACHE_BASEDIR=${CMAKE_SOURCE_DIR} CCACHE_NOHASHDIR=1 ${RAYCACHE_CCACHE_PROGRAM})
    if(CMAKE_BUILD_TYPE MATCHES "Deb")
      add_compile_options(-fdebug-prefix-map=${CMAKE_SOURCE_DIR}=.)
    endif()
  endif()
endif()
