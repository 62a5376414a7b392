# Link with lld when it is installed (scripts/install-deps.sh installs it).
# The release and asan presets link some fifty programs each, and lld links
# them faster than GNU ld (measured: docs/testing.md, "Where the time goes").
# The programs' code is the same either way.
option(RAYCACHE_LLD "Link with lld when it is installed" ON)
if(RAYCACHE_LLD)
  include(CheckLinkerFlag)
  check_linker_flag(CXX "-fuse-ld=lld" RAYCACHE_LINKER_LLD)
  if(RAYCACHE_LINKER_LLD)
    add_link_options(-fuse-ld=lld)
  endif()
endif()
