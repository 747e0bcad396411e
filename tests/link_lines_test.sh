#!/usr/bin/env bash
# The formats layer and what stands on it alone must not be linked with a ray tracer or model
# importers: the link lines CMake wrote (<build>/<folder>/CMakeFiles/<target>.dir/link.txt) of the
# given targets may not name Embree, assimp, tinygltf or draco (docs/architecture.md).
# Usage: link_lines_test.sh BUILD_DIR FOLDER/TARGET...
set -u
build=$1; shift
status=0
for target in "$@"; do
  link="$build/$(dirname "$target")/CMakeFiles/$(basename "$target").dir/link.txt"
  if [ ! -f "$link" ]; then
    echo "FAILED: no link line at $link (this test reads the Makefile generator's link.txt)"
    status=1
    continue
  fi
  found=$(grep -Eo 'lib(embree|assimp|tinygltf|draco)[^ ]*' "$link" | sort -u | tr '\n' ' ')
  if [ -n "$found" ]; then
    echo "FAILED: $target links $found"
    status=1
  else
    echo "ok: $target links no Embree, assimp, tinygltf or draco"
  fi
done
exit $status
