# Sourced by the build scripts: compile through ccache (Debian's package), with a cache outside
# the checkout that survives between runs on the same machine and is shared by every clone:
# paths below the checkout are hashed relative to it (CCACHE_BASEDIR) and the build folder is not
# hashed (CCACHE_NOHASHDIR), so a fresh clone elsewhere hits the objects of the last one (the
# test build's; the main job's unity files include the sources by absolute path).
# 5 GB holds the Release and the sanitizer trees with room for a few versions of each.
home=${HOME:-$(getent passwd "$(id -u)" | cut -d: -f6)}
export CCACHE_DIR=${CCACHE_DIR:-${XDG_CACHE_HOME:-$home/.cache}/mtacc-ccache}
# Always this checkout (the scripts run from its root): a base folder inherited from a shell
# that sourced this file in another clone would make every object of this one miss.
export CCACHE_BASEDIR=$(pwd)
export CCACHE_NOHASHDIR=1
# Depend mode: on a miss, ccache takes the headers from the compiler's own -MD output instead of
# running the preprocessor a second time (CMake passes -MD to GCC and clang).
export CCACHE_DEPEND=1
mkdir -p "$CCACHE_DIR"
ccache --max-size=5G > /dev/null
ccache --zero-stats > /dev/null
ccache_launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
# One line on what the build just took from the cache: ccache_summary FOLDER
ccache_summary() { echo "compiler cache ($1): $(ccache --show-stats | grep -m1 -E '^ *Hits:' | sed 's/^ *//')"; }
