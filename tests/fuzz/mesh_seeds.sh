#!/usr/bin/env bash
# Writes the mesh fuzzer's seed corpus: every model of Debian's assimp-testmodels up to 32 KiB
# (its malformed ones in models/invalid included) as "<extension>\n<file bytes>", the input form
# of tests/fuzz/fuzz_mesh.cpp. Usage: mesh_seeds.sh MODELS_DIR OUT_DIR
set -euo pipefail
models=$1
out=$2
if [ ! -d "$models" ]; then
  echo "mesh_seeds.sh: $models not found (expected Debian's assimp-testmodels)" >&2
  exit 1
fi
mkdir -p "$out"
n=0
while IFS= read -r -d '' file; do
  name=$(basename "$file")
  ext=${name##*.}
  [ "$ext" = "$name" ] && continue
  ext=$(printf '%s' "$ext" | tr 'A-Z' 'a-z')
  case $ext in
    obj|ply|stl|off|3ds|ase|lwo|x|smd|md5mesh|raw|nff|ac|dae|gltf|glb|fbx|blend|amf|cob|ms3d|xml|\
    irrmesh|m3d|md2|md3|mdl|q3o|q3s|ogex|3d|b3d|csm|hmp|ndo|ter|x3d|zgl|iqm|xgl|dxf|lws|bvh|ask) ;;
    *) continue ;;
  esac
  n=$((n + 1))
  { printf '%s\n' "$ext"; cat "$file"; } > "$out/$(printf '%04d' $n)_$name"
done < <(find "$models" -type f -size -33k -print0 | sort -z)
echo "mesh_seeds.sh: $n seeds in $out"
