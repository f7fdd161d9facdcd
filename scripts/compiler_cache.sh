# Sourced by the build scripts: compile through ccache when it is installed (scripts/setup.sh installs
# it), with paths taken relative to the checkout and the build folder left out of the hash (debug info
# then names paths relative to it), so that clones in other folders share the cache.
compiler_cache=()
if command -v ccache >/dev/null 2>&1; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  compiler_cache=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
