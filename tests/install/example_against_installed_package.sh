#!/usr/bin/env bash
# The README's C++ example (checked to be the same text as examples/drop_ragdoll.cpp), built as a
# user builds it: the library installed into a fresh prefix, examples/ configured as a separate
# project that finds it with find_package(af), then run on the source tree's sample data. Fails unless the ragdoll rests with its joints closed and every joint
# of its skeleton is reported above the floor.
# Usage: example_against_installed_package.sh BUILD_DIR SOURCE_DIR WORK_DIR CXX_COMPILER
set -euo pipefail
build=$1 source=$2 work=$3 cxx=$4

rm -rf "$work"
mkdir -p "$work"

# The README shows this program in full; the two must not drift apart.
awk '/^```cpp$/ {inside = 1; next} /^```$/ {inside = 0} inside' "$source/README.md" > "$work/readme_example.cpp"
if ! diff -u "$source/examples/drop_ragdoll.cpp" "$work/readme_example.cpp"; then
    echo "README.md's C++ example differs from examples/drop_ragdoll.cpp" >&2
    exit 1
fi
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
# The installed headers are the public API and nothing more: each includes only others of them.
if grep -rn '#include "' "$work/prefix/include/af" | grep -v '#include "af/'; then
    echo "an installed header includes a header that is not installed" >&2
    exit 1
fi
cmake -S "$source/examples" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
cmake --build "$work/build" > "$work/build.log"
"$work/build/drop_ragdoll" "$source" | tee "$work/out.txt"

awk '
    NR == 1 {
        if ($2 != "at" || $3 != "rest") { print "not at rest: " $0; bad = 1 }
        if ($NF != "units" || $(NF - 1) + 0 > 1e-6) { print "joint error too large: " $0; bad = 1 }
        next
    }
    { joints++; if ($4 < -0.5 || $4 > 40) { print "joint off the floor or still high: " $0; bad = 1 } }
    END {
        if (joints != 25) { print "expected the 25 joints of the humanoid skeleton, got " joints; bad = 1 }
        exit bad
    }' "$work/out.txt"
echo "example: built against the installed package and ran"
