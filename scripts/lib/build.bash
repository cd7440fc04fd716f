# Shared by the scripts that build glint (sourced, not run).

# glint_configure SOURCE BUILD [CMAKE_OPTION...]: configures the build directory BUILD, with
# Ninja where it is installed (it records what each file costs: scripts/build-times) unless
# BUILD was configured before, which keeps its generator (CMake refuses to change it).
glint_configure() {
  local source=$1 build=$2
  shift 2
  local generator=()
  if [[ ! -f $build/CMakeCache.txt ]] && command -v ninja >/dev/null; then
    generator=(-G Ninja)
  fi
  cmake -S "$source" -B "$build" "${generator[@]}" "$@"
}
