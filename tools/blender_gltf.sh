#!/usr/bin/env bash
# A glTF file as Blender 3.4 exports it, rendered by Kappa with its camera,
# lights and materials: tools/blender/gltf_export_scene.py builds the scene
# and exports it with Blender's glTF add-on to build/scenes/blender/scene.glb,
# then `kappa render` renders it and the script checks what the report says
# it read (one camera, three punctual lights, the materials, no refusal).
#   tools/blender_gltf.sh [SPP]
# Needs Blender (Debian's `blender`, 3.4); the test suite does not: it skips
# with exit 0 and a line when Blender is not installed.
set -euo pipefail
cd "$(dirname "$0")/.."
spp="${1:-64}"
if ! command -v blender >/dev/null; then
  echo "blender_gltf: Blender is not installed (apt-get install blender): nothing done"
  exit 0
fi
out=build/scenes/blender
mkdir -p "$out"
blender -b --factory-startup --python tools/blender/gltf_export_scene.py -- "$out/scene.glb" >"$out/blender.log" 2>&1 || {
  echo "blender_gltf: Blender failed, see $out/blender.log" >&2
  exit 1
}
# Lit by its own lights alone, as Blender renders a scene without a world
# (a bare glTF file gets Kappa's white environment); seen through its camera.
echo '{"meshes": ["scene.glb"], "environment": [0, 0, 0]}' >"$out/scene.json"
[ -x build/kappa ] || tools/build.sh
build/kappa render "$out/scene.json" --spp "$spp" --out "$out/scene.exr" --report "$out/report.json" \
  --preview "$out/scene.png" 2>"$out/kappa.log" || {
  cat "$out/kappa.log" >&2
  exit 1
}
cat "$out/kappa.log"
/usr/bin/python3 - "$out/report.json" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
g = r["gltf"][0]
print(f"blender_gltf: {g['file']}: {g['nodes']} nodes, {g['meshes']} meshes, {g['materials']} materials, "
      f"{g['triangles']} triangles, camera {r['camera']}, {r['punctual_lights']} punctual lights, "
      f"path variant '{r['render']['path_variant']}', {r['render']['width']}x{r['render']['height']}")
assert r["camera"] is not None, "the exported camera was not used"
assert r["punctual_lights"] == 3, "expected the point, spot and sun lights"
assert g["materials"] >= 5, "expected the five materials"
EOF
echo "blender_gltf: rendered $out/scene.exr (preview $out/scene.png)"
