# Shared by scripts/run and scripts/test (sourced, not run): installs the Debian packages that are
# missing, then configures and builds Brume in build/ (override with BRUME_BUILD_DIR).

BRUME_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BRUME_BUILD="${BRUME_BUILD_DIR:-$BRUME_ROOT/build}"
BRUME_SANITIZE_BUILD="${BRUME_SANITIZE_BUILD_DIR:-$BRUME_ROOT/build-sanitize}"

# ccache keys on absolute paths and, with debug info, on the build folder: rewriting paths under the
# checkout as relative ones lets a fresh clone elsewhere (CI's, a second worktree) reuse the cache.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$BRUME_ROOT}"
export CCACHE_NOHASHDIR="${CCACHE_NOHASHDIR:-1}"

BRUME_PACKAGES=(
  cmake g++ pkg-config ccache
  libopenvdb-dev libnanovdb-dev libboost-iostreams-dev
  libvulkan-dev mesa-vulkan-drivers glslang-tools glslang-dev spirv-tools vulkan-validationlayers
  libglm-dev libimgui-dev libglfw3-dev libstb-dev libopenexr-dev nlohmann-json3-dev libcli11-dev
  libgtest-dev libbenchmark-dev
  xvfb xauth xdotool
  python3  # bench/compare_builds.py (A/B timing of builds) and its test
  slurm-wlm  # tests/slurm_farm.sh: a one-node Slurm on localhost (32 s to install, daemons up in 1 s)
  clang libclang-rt-14-dev
)

brume_missing_packages() {
  local p
  for p in "${BRUME_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      echo "$p"
    fi
  done
}

# apt-get runs only when something is missing, so a ready machine builds offline.
brume_install_deps() {
  local missing
  mapfile -t missing < <(brume_missing_packages)
  if [[ ${#missing[@]} -eq 0 ]]; then
    return 0
  fi
  echo "brume: installing missing packages: ${missing[*]}"
  local sudo=()
  if [[ "$(id -u)" -ne 0 ]]; then
    sudo=(sudo)
  fi
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y "${missing[@]}"
}

brume_build() {
  # ccache, where installed, makes rebuilds after a branch switch or a clean clone cheap.
  local launcher=()
  if command -v ccache >/dev/null 2>&1; then
    launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  fi
  cmake -S "$BRUME_ROOT" -B "$BRUME_BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo "${launcher[@]}"
  cmake --build "$BRUME_BUILD" -j"$(nproc)"
}

# The instrumented build in build-sanitize/: clang with ASan + UBSan and libFuzzer's coverage hooks
# (BRUME_FUZZ), without the GPU renderer, the editor window and the benchmarks. One build serves
# scripts/test --sanitize (the tests, where the hooks do nothing) and scripts/fuzz (the libFuzzer
# targets), so CI compiles the instrumented libraries once. -O1 (ASan's advice) and -g1 (line
# tables for the reports) keep the OpenVDB units' compile time down. ccache is used when present.
# Arguments: the targets to build (none: all).
brume_build_sanitized() {
  local launcher=()
  if command -v ccache >/dev/null; then
    launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  fi
  CC=clang CXX=clang++ cmake -S "$BRUME_ROOT" -B "$BRUME_SANITIZE_BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DBRUME_FUZZ=ON -DBRUME_BUILD_GPU=OFF -DBRUME_BUILD_BENCH=OFF "${launcher[@]}" >/dev/null
  local targets=()
  if [[ $# -gt 0 ]]; then
    targets=(--target "$@")
  fi
  cmake --build "$BRUME_SANITIZE_BUILD" -j"${BRUME_JOBS:-$(nproc)}" "${targets[@]}"
}
