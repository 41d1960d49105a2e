# Sourced by setup.sh and sanitize.sh: compile through ccache where it is
# installed (setup.sh installs it), so that a rebuild, and CI's builds after
# the first on a machine, compile only what changed. Sets the array
# `compiler_cache` to the CMake options (empty without ccache).
#
# What ccache needs here: paths taken relative to the source folder (two
# clones share their objects where nothing compiled names an absolute path;
# the tests' objects do, BEAMSLIDER_SOURCE_DIR, so .ci/run builds in one
# fixed folder), the debug info's folder left out of the key (-g1 in the
# sanitizer build), and the precompiled headers accepted (CMake's PCH:
# their defines and time macros, and the header's mtime, are the cache's
# to trust; a changed header still changes its hash).
compiler_cache=()
if command -v ccache > /dev/null 2>&1; then
  export CCACHE_BASEDIR="$PWD"
  export CCACHE_NOHASHDIR=1
  export CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
  compiler_cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
