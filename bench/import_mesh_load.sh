#!/usr/bin/env bash
# Loading a 10^6-triangle PLY through a Mitsuba scene (XML, converted) against through the
# grinlight scene that says the same: a 1 × 1 render of one sample, 5 runs each, medians.
#   bash bench/import_mesh_load.sh
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --quiet
exe="$PWD/target/release/grinlight"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
python3 - "$dir/mesh.ply" <<'PY'
import sys, numpy as np
n = 708  # (n-1)^2 * 2 ≈ 10^6 triangles on a bumpy sheet
x, y = np.meshgrid(np.linspace(-1, 1, n), np.linspace(-1, 1, n))
z = 0.05 * np.sin(8 * x) * np.cos(8 * y)
v = np.stack([x, y, z], axis=-1).reshape(-1, 3).astype('<f4')
i = np.arange(n * n).reshape(n, n)
a, b, c, d = i[:-1, :-1].ravel(), i[:-1, 1:].ravel(), i[1:, 1:].ravel(), i[1:, :-1].ravel()
f = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)]).astype('<i4')
with open(sys.argv[1], 'wb') as out:
    out.write(f"ply\nformat binary_little_endian 1.0\nelement vertex {len(v)}\nproperty float x\nproperty float y\nproperty float z\nelement face {len(f)}\nproperty list uchar int vertex_indices\nend_header\n".encode())
    out.write(v.tobytes())
    rec = np.zeros(len(f), dtype=[('n', 'u1'), ('i', '<i4', 3)])
    rec['n'] = 3; rec['i'] = f
    out.write(rec.tobytes())
print(f"{len(f)} triangles", file=sys.stderr)
PY
cat > "$dir/s.xml" <<'XML'
<scene version="3.0.0">
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, 3" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
        <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film>
    </sensor>
    <emitter type="point"><point name="position" value="0, 0, 2"/></emitter>
    <shape type="ply"><string name="filename" value="mesh.ply"/>
        <boolean name="face_normals" value="true"/>
        <bsdf type="twosided"><bsdf type="diffuse"/></bsdf></shape>
</scene>
XML
"$exe" convert "$dir/s.xml" -o "$dir/s.toml" 2>/dev/null
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
time_of() {
    for _ in 1 2 3 4 5; do
        /usr/bin/env time -f %e "$exe" render "$1" -o "$dir/out.exr" --threads 2 2>&1 >/dev/null | tail -1
    done | median
}
xml=$(time_of "$dir/s.xml")
toml=$(time_of "$dir/s.toml")
printf "%-28s %8s\n" "scene" "median s"
printf "%-28s %8s\n" "PLY via the XML" "$xml"
printf "%-28s %8s\n" "PLY via the converted TOML" "$toml"
awk -v a="$xml" -v b="$toml" 'BEGIN {printf "ratio XML / TOML: %.3f\n", a / b}'
