#!/usr/bin/env bash
# Builds the `device` preset (release, no OpenImageIO: its libraries are too
# large to carry) and gathers what a machine without our packages needs to
# run the GPU path into .dev/ (git-ignored through .git/info/exclude):
#   .dev/bin/   habuffer (no image files), habuffer_gl_tests,
#               habuffer_render_tests, habuffer_bench, habuffer_adaptive_jumps,
#               habuffer_vk_tests (where the Vulkan path is built)
#   .dev/lib/   the shared libraries they load beyond the C/C++ runtime
#               (oneTBB, libepoxy, assimp and its codecs, Google Benchmark)
#   .dev/models the assimp-testmodels files the named scenes read
#   .dev/run.sh the environment: LD_LIBRARY_PATH, HABUFFER_ASSIMP_MODELS
# The GL loader itself (glvnd's libEGL, libOpenGL) comes from the .gl/
# packages the device README names; the NVIDIA driver is the machine's.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh device >/dev/null
rm -rf .dev && mkdir -p .dev/bin .dev/lib .dev/models
bins=(habuffer habuffer_gl_tests habuffer_render_tests habuffer_bench habuffer_adaptive_jumps)
# The Vulkan tests where the build has the Vulkan path; the Vulkan loader
# (libvulkan.so.1) is carried with the other libraries, NVIDIA's ICD is the machine's.
[ -x build-device/bin/habuffer_vk_tests ] && bins+=(habuffer_vk_tests)
for b in "${bins[@]}"; do strip -o ".dev/bin/$b" "build-device/bin/$b"; done
# Every library ldd resolves, except the C/C++ runtime and the GL loaders
# (the device machine has the runtime; the loaders come from .gl/).
for b in "${bins[@]}"; do ldd "build-device/bin/$b"; done | awk '$3 ~ /^\// {print $1, $3}' | sort -u |
  while read -r name path; do
    case "$name" in
      libc.so*|libm.so*|libstdc++*|libgcc_s*|libpthread*|libdl.so*|librt.so*|ld-linux*|libEGL*|libGL*|libOpenGL*|libGLdispatch*|libGLX*) ;;
      *) cp -L "$path" ".dev/lib/$name" ;;
    esac
  done
models=${HABUFFER_ASSIMP_MODELS:-/usr/share/assimp/models}
for f in glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb PLY/Wuson.ply OBJ/spider.obj OBJ/spider.mtl; do
  [ -f "$models/$f" ] && { mkdir -p ".dev/models/$(dirname "$f")"; cp "$models/$f" ".dev/models/$f"; }
done
cat > .dev/run.sh <<'RUN'
# Sourced on the device machine from the repository root.
export LD_LIBRARY_PATH="$PWD/.dev/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export HABUFFER_ASSIMP_MODELS="$PWD/.dev/models"
export PATH="$PWD/.dev/bin:$PATH"
RUN
du -sh .dev
